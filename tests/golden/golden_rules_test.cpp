// The core's traversal rules (docs/architecture.md), each checked on a hand-built tree where the
// rule decides the outcome: rays in a split plane, zero direction components, packets whose rays
// disagree in direction, ties at a shared edge, rays starting inside a leaf, misses, and the stack
// at and beyond its depth.
#include <gtest/gtest.h>

#include <array>
#include <glm/geometric.hpp>
#include <random>
#include <vector>

#include "compiler.hpp"
#include "fp.hpp"
#include "hand_geometry.hpp"
#include "image.hpp"
#include "trace.hpp"

namespace rc::test {
namespace {

using T = fp24;
using scene::KdNode;

using hand::add_quad;
using hand::add_tri;
using hand::f;
using hand::ray;
using hand::set_box;

struct Traced {
  std::array<Hit<T>, kPacketRays> hits;
  Counters c;
  uint32_t err;
};

Traced trace(const Geometry<T>& g, std::array<Ray<T>, kPacketRays> rays, uint32_t mask) {
  Traced t;
  t.err = trace_packet(g, rays, mask, t.hits, t.c);
  return t;
}

Traced trace1(const Geometry<T>& g, const Ray<T>& r) { return trace(g, {r, r, r, r}, 1u); }

// Root splits x at 0. Left leaf: a square at z = -5; right leaf: a square at z = -3. Both squares
// span x in [-1, 1], but each is listed in one leaf only, so which leaves a ray visits decides
// what it hits.
Geometry<T> two_leaf_scene(std::array<uint32_t, 2>& left, std::array<uint32_t, 2>& right) {
  Geometry<T> g;
  left = add_quad(g, -1, 1, -1, 1, -5);
  right = add_quad(g, -1, 1, -1, 1, -3);
  g.nodes = {KdNode::inner(0, 1, f(0.0).bits()).raw, KdNode::leaf(0, 2).raw,
             KdNode::leaf(2, 2).raw};
  g.lists = {left[0], left[1], right[0], right[1]};
  set_box(g, -8, 8);
  return g;
}

TEST(GoldenRules, RayInSplitPlaneVisitsBothChildren) {
  std::array<uint32_t, 2> l, r;
  const Geometry<T> g = two_leaf_scene(l, r);
  // origin on the plane x = 0, direction component +0 and -0: t is NaN, both children visited
  for (double dx : {0.0, -0.0}) {
    const Traced t = trace1(g, ray({0.0, 0.25, 0.0}, {dx, 0.0, -1.0}));
    EXPECT_EQ(t.err, 0u);
    EXPECT_EQ(t.c.leaf_visits, 2u) << "dx=" << dx;
    EXPECT_TRUE(t.hits[0].tri == static_cast<int32_t>(r[0]) ||
                t.hits[0].tri == static_cast<int32_t>(r[1]));
    EXPECT_EQ(t.hits[0].t.to_double(), 3.0);
  }
}

TEST(GoldenRules, ZeroDirectionComponentStaysOnItsSide) {
  std::array<uint32_t, 2> l, r;
  const Geometry<T> g = two_leaf_scene(l, r);
  for (double dx : {0.0, -0.0}) {
    // origin left of the plane: only the left leaf (t = (0 - x) * +-inf is +-inf, never NaN)
    Traced t = trace1(g, ray({-0.5, 0.25, 0.0}, {dx, 0.0, -1.0}));
    EXPECT_EQ(t.c.leaf_visits, 1u);
    EXPECT_TRUE(t.hits[0].tri == static_cast<int32_t>(l[0]) ||
                t.hits[0].tri == static_cast<int32_t>(l[1]));
    EXPECT_EQ(t.hits[0].t.to_double(), 5.0);
    // origin right of the plane: only the right leaf
    t = trace1(g, ray({0.5, 0.25, 0.0}, {dx, 0.0, -1.0}));
    EXPECT_EQ(t.c.leaf_visits, 1u);
    EXPECT_EQ(t.hits[0].t.to_double(), 3.0);
  }
  // a subnormal encoding reads as zero too
  Ray<T> rs = ray({-0.5, 0.25, 0.0}, {0.0, 0.0, -1.0});
  rs.dir[0] = T::from_bits(1);
  const Traced t = trace1(g, rs);
  EXPECT_EQ(t.c.leaf_visits, 1u);
  EXPECT_EQ(t.hits[0].t.to_double(), 5.0);
}

// The root-box clip: a ray that misses the box fetches no node; a ray lying in a face plane of the
// box (origin on the face, direction component zero: t is NaN) is inside along that axis.
TEST(GoldenRules, RootBoxClip) {
  std::array<uint32_t, 2> l, r;
  Geometry<T> g = two_leaf_scene(l, r);
  set_box(g, -1, 1);
  g.bounds[2] = f(-5);  // z from -5 to 1
  Traced t = trace1(g, ray({3.0, 0.0, 0.0}, {0.0, 0.0, -1.0}));
  EXPECT_EQ(t.hits[0].tri, -1);
  EXPECT_EQ(t.c.nodes_fetched, 0u) << "a ray outside the box never enters the tree";
  for (double dx : {0.0, -0.0}) {
    t = trace1(g, ray({-1.0, 0.25, 0.0}, {dx, 0.0, -1.0}));  // in the face plane x = -1
    EXPECT_EQ(t.hits[0].t.to_double(), 5.0) << "dx=" << dx;
    t = trace1(g, ray({1.0, 0.25, 0.0}, {dx, 0.0, -1.0}));  // in the face plane x = +1
    EXPECT_EQ(t.hits[0].t.to_double(), 3.0) << "dx=" << dx;
  }
  // a ray starting outside and entering through a face starts its interval at the entry
  t = trace1(g, ray({0.5, 0.25, 4.0}, {0.0, 0.0, -1.0}));
  EXPECT_EQ(t.hits[0].t.to_double(), 7.0);
}

TEST(GoldenRules, MissesReportNoHit) {
  std::array<uint32_t, 2> l, r;
  const Geometry<T> g = two_leaf_scene(l, r);
  const Traced t = trace(g,
                         {ray({0.5, 0.5, 0.0}, {0, 0, 1}), ray({-0.5, 0.5, 0.0}, {0, 0.2, 1}),
                          ray({3.0, 0.0, 0.0}, {0, 0, -1}), ray({0, 0, -10}, {0, 0, -1})},
                         0xf);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(t.hits[i].tri, -1) << "ray " << i;
  EXPECT_EQ(t.c.errors, 0u);
}

// A shared edge: triangle `lo` and `hi` meet along x + y = 1; a ray through the edge's midpoint
// hits both at the same t, and the lower triangle index wins whatever the list order.
TEST(GoldenRules, TieAtSharedEdgeGoesToLowerIndex) {
  for (bool lower_first : {false, true}) {
    Geometry<T> g;
    const uint32_t a = add_tri(g, {0, 0, -2}, {1, 0, -2}, {0, 1, -2});
    const uint32_t b = add_tri(g, {1, 0, -2}, {1, 1, -2}, {0, 1, -2});
    g.nodes = {KdNode::leaf(0, 2).raw};
    set_box(g, -4, 4);
    g.lists = lower_first ? std::vector<uint32_t>{a, b} : std::vector<uint32_t>{b, a};
    const Ray<T> r = ray({0.5, 0.5, 0.0}, {0, 0, -1});
    Hit<T> best, h;
    best.t = T::inf();
    ASSERT_TRUE(intersect(g.tris[a], r, 0, best, h)) << "the edge point must hit a";
    ASSERT_TRUE(intersect(g.tris[b], r, 1, best, h)) << "the edge point must hit b";
    const Traced t = trace1(g, r);
    EXPECT_EQ(t.hits[0].tri, static_cast<int32_t>(a)) << "list order " << lower_first;
  }
}

// Brute force over every triangle with the same intersection unit: the closest hit by (t, index).
Hit<T> brute_force(const Geometry<T>& g, const Ray<T>& r) {
  Hit<T> best, h;
  best.t = T::inf();
  for (size_t i = 0; i < g.tris.size(); ++i)
    if (intersect(g.tris[i], r, static_cast<int32_t>(i), best, h)) best = h;
  return best;
}

// A 4x4x4 grid of leaves (inner nodes split x, then y, then z at -1, 0, 1), each leaf holding
// every small random triangle that lies in its cell; rays start inside leaves and point anywhere.
struct GridScene {
  Geometry<T> g;
};

GridScene grid_scene(uint64_t seed) {
  GridScene s;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-1.9, 1.9), off(-0.6, 0.6);
  std::vector<std::array<glm::dvec3, 3>> tris;
  for (int i = 0; i < 600; ++i) {
    const glm::dvec3 c(pos(rng), pos(rng), pos(rng));
    tris.push_back({c, c + glm::dvec3(off(rng), off(rng), off(rng)),
                    c + glm::dvec3(off(rng), off(rng), off(rng))});
  }
  for (auto& t : tris) add_tri(s.g, t[0], t[1], t[2]);
  set_box(s.g, -2.6, 2.6);
  // Build the tree: axis by depth (x, y, z), splits at -1, 0, 1 (two levels per axis).
  struct Box {
    glm::dvec3 lo, hi;
  };
  std::vector<uint64_t>& nodes = s.g.nodes;
  std::vector<std::pair<uint32_t, Box>> todo;
  nodes.push_back(0);
  todo.push_back({0, {glm::dvec3(-2), glm::dvec3(2)}});
  for (size_t k = 0; k < todo.size(); ++k) {
    const auto [idx, box] = todo[k];
    int axis = -1;
    for (int a = 0; a < 3 && axis < 0; ++a)
      if (box.hi[a] - box.lo[a] > 1.5) axis = a;
    if (axis < 0) {  // leaf: every triangle whose box overlaps the cell
      const auto first = static_cast<uint32_t>(s.g.lists.size());
      for (uint32_t t = 0; t < tris.size(); ++t) {
        bool overlap = true;
        for (int a = 0; a < 3; ++a) {
          const double lo = std::min({tris[t][0][a], tris[t][1][a], tris[t][2][a]});
          const double hi = std::max({tris[t][0][a], tris[t][1][a], tris[t][2][a]});
          overlap = overlap && hi >= box.lo[a] && lo <= box.hi[a];
        }
        if (overlap) s.g.lists.push_back(t);
      }
      nodes[idx] = KdNode::leaf(first, static_cast<uint32_t>(s.g.lists.size()) - first).raw;
      continue;
    }
    const double split = (box.lo[axis] + box.hi[axis]) / 2;
    const auto left = static_cast<uint32_t>(nodes.size());
    nodes.push_back(0);
    nodes.push_back(0);
    nodes[idx] = KdNode::inner(axis, left, f(split).bits()).raw;
    Box l = box, r = box;
    l.hi[axis] = split;
    r.lo[axis] = split;
    todo.push_back({left, l});
    todo.push_back({left + 1, r});
  }
  return s;
}

// Packets whose rays start inside leaves and disagree in direction along every axis give the same
// hits as the rays traced alone, and as brute force over all triangles.
TEST(GoldenRules, MixedSignPacketsAndRaysInsideLeavesMatchSingleRays) {
  const GridScene s = grid_scene(7);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(-1.9, 1.9), dir(-1.0, 1.0);
  uint64_t rays = 0, mismatches = 0, hits = 0;
  for (int p = 0; p < 4000; ++p) {
    std::array<Ray<T>, kPacketRays> pk;
    for (auto& r : pk) r = ray({pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)});
    const Traced t = trace(s.g, pk, 0xf);
    ASSERT_EQ(t.err, 0u);
    for (int i = 0; i < kPacketRays; ++i) {
      const Traced alone = trace1(s.g, pk[i]);
      const Hit<T> bf = brute_force(s.g, pk[i]);
      ++rays;
      hits += t.hits[i].tri >= 0;
      const bool same = t.hits[i].tri == alone.hits[0].tri && t.hits[i].tri == bf.tri &&
                        t.hits[i].t.bits() == bf.t.bits();
      if (!same && ++mismatches <= 5)
        ADD_FAILURE() << "packet " << p << " ray " << i << ": packet " << t.hits[i].tri
                      << ", alone " << alone.hits[0].tri << ", brute force " << bf.tri;
    }
  }
  std::printf(
      "[cases] golden packets vs single rays vs brute force: %llu cases, %llu mismatches "
      "(%llu hits)\n",
      static_cast<unsigned long long>(rays), static_cast<unsigned long long>(mismatches),
      static_cast<unsigned long long>(hits));
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(hits, rays / 10) << "the scene should be hit often enough to test something";
}

// A chain of inner nodes, each pushing its far child: depth `pushes` needs `pushes` stack entries.
Geometry<T> push_chain(int pushes) {
  Geometry<T> g;
  const uint32_t tri = add_tri(g, {-1, -1, 0.5}, {1, -1, 0.5}, {-1, 1, 0.5});
  // inner node k splits x at 0.01 * (pushes - k); its left child is the next inner node,
  // its right child an empty leaf; the last inner node's left child is a leaf with the triangle.
  g.lists = {tri};
  g.nodes.assign(static_cast<size_t>(2 * pushes + 1), 0);
  for (int k = 0; k < pushes; ++k) {
    const uint32_t idx = k == 0 ? 0u : static_cast<uint32_t>(2 * k - 1);
    const auto left = static_cast<uint32_t>(2 * k + 1);
    g.nodes[idx] = KdNode::inner(0, left, f(0.01 * (pushes - k)).bits()).raw;
    g.nodes[left + 1] = KdNode::leaf(0, 0).raw;
  }
  g.nodes[static_cast<size_t>(2 * pushes - 1)] = KdNode::leaf(0, 1).raw;
  set_box(g, -1, 1);
  g.bounds[5] = f(100.0);  // z up to 100: the ray below crosses every split before leaving
  return g;
}

TEST(GoldenRules, StackAtItsDepthWorksAndOneMoreOverflows) {
  const int depth = static_cast<int>(spec::kKdtreeStackDepth);
  const Ray<T> r = ray({-0.5, 0.0, 0.0}, {0.01, 0.0, 1.0});  // crosses every split plane at t > 0
  Traced t = trace1(push_chain(depth), r);
  EXPECT_EQ(t.err, 0u);
  EXPECT_EQ(t.c.max_stack, static_cast<uint64_t>(depth));
  EXPECT_EQ(t.hits[0].tri, 0);
  t = trace1(push_chain(depth + 1), r);
  EXPECT_EQ(t.err, static_cast<uint32_t>(kErrStackOverflow));
  EXPECT_EQ(t.hits[0].tri, -1) << "a failed packet reports misses";
  EXPECT_EQ(t.c.errors, 1u);
}

TEST(GoldenRules, MalformedNodesAndBadAddressesSetErrorBits) {
  std::array<uint32_t, 2> l, r;
  const Ray<T> ry = ray({0.5, 0.25, 0.0}, {0, 0, -1});
  Geometry<T> g = two_leaf_scene(l, r);
  g.nodes[0] = KdNode::inner(0, 2, f(0.0).bits()).raw;  // children 2 and 3: 3 is out of range
  EXPECT_EQ(trace1(g, ry).err, static_cast<uint32_t>(kErrMalformedNode));
  g = two_leaf_scene(l, r);
  g.nodes[0] = KdNode::inner(0, 1, T::nan().bits()).raw;
  EXPECT_EQ(trace1(g, ry).err, static_cast<uint32_t>(kErrMalformedNode));
  g = two_leaf_scene(l, r);
  g.nodes[2] = KdNode::inner(1, 0, f(0.0).bits()).raw;  // a child pointing back at the root
  EXPECT_EQ(trace1(g, ry).err, static_cast<uint32_t>(kErrMalformedNode)) << "a cycle must end";
  g = two_leaf_scene(l, r);
  g.nodes[2] = KdNode::leaf(3, 2).raw;  // list entries 3..4: 4 is outside
  EXPECT_EQ(trace1(g, ry).err, static_cast<uint32_t>(kErrBadAddress));
  g = two_leaf_scene(l, r);
  g.lists[2] = 99;  // no triangle 99
  EXPECT_EQ(trace1(g, ry).err, static_cast<uint32_t>(kErrBadAddress));
}

}  // namespace
}  // namespace rc::test
