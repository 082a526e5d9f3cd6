// The refraction rules (docs/architecture.md, "Refraction"), each checked where it decides the
// outcome: the direction against Snell's law in double, entering and leaving, total internal
// reflection (the mirror direction), a glass pane that shows the floor below it (the weighted
// terms, the refraction ray's hit), a material that both reflects and refracts (the tree
// branches, and both kinds of ray count against one depth), a weight that underflows.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "fp.hpp"
#include "hand_geometry.hpp"
#include "trace.hpp"

namespace rc::test {
namespace {

using T = fp24;
using scene::KdNode;

using hand::add_material;
using hand::add_quad;
using hand::f;
using hand::ray;
using hand::set_box;

constexpr double kAmbient = static_cast<double>(spec::kShadeAmbientPermille) / 1000.0;

double byte_of_term(double x) {
  const double fx = std::nearbyint(std::min(std::max(x, 0.0), 1.0) * kLightOne);
  return std::nearbyint(fx * 255.0 / kLightOne);
}

// Glass panes (each a square facing +z, the glass material) above an opaque red floor at z = -8,
// all in one leaf, with a directional light straight above. The ray from (-3, 0, 0) along
// (1, 0, -1) meets the first pane (z = -5) at (2, 0, -5).
struct PaneScene {
  Geometry<T> g;
  std::vector<std::array<uint32_t, 2>> panes;
  std::array<uint32_t, 2> floor;
  PaneScene(std::vector<double> pane_z, double mirror, double transmit, double ior = 1.5) {
    const uint32_t red = add_material(g, {1.0, 0.0, 0.0});
    const uint32_t glass = add_material(g, {0.0, 0.0, 0.0}, mirror, transmit, ior);
    for (double z : pane_z) {
      panes.push_back(add_quad(g, -8, 8, -8, 8, z));
      for (uint32_t t : panes.back()) g.material[t] = glass;
    }
    floor = add_quad(g, -8, 8, -8, 8, -8);
    for (uint32_t t : floor) g.material[t] = red;
    g.nodes = {KdNode::leaf(0, static_cast<uint32_t>(g.tris.size())).raw};
    for (uint32_t t = 0; t < g.tris.size(); ++t) g.lists.push_back(t);
    set_box(g, -9, 9);
    g.t_eps = f(18.0 * std::sqrt(3.0) / 4096.0);
    Geometry<T>::Light l;
    l.directional = true;
    l.pos = {f(0.0), f(0.0), f(1.0)};
    l.color = {f(1.0), f(1.0), f(1.0)};
    g.lights = {l};
  }
};

const Ray<T> kPaneRay = ray({-3, 0, 0}, {1, 0, -1});

struct Shaded {
  LitPacket p;
  LitCounters c;
};

Shaded shade_one(const Geometry<T>& g, const Ray<T>& r, uint32_t max_bounces) {
  Shaded s;
  std::array<Hit<T>, kPacketRays> hits;
  Counters primary;
  EXPECT_EQ(trace_packet(g, {r, r, r, r}, 0x1u, hits, primary), 0u);
  s.p = shade_lit(g, {r, r, r, r}, 0x1u, hits, lit_params<T>(max_bounces, {0, 0, 0}), s.c);
  return s;
}

// The surface point of ray r's hit on g (which must hit).
SurfacePoint<T> hit_point(const Geometry<T>& g, const Ray<T>& r, Hit<T>* hit) {
  std::array<Hit<T>, kPacketRays> hits;
  Counters c;
  EXPECT_EQ(trace_packet(g, {r, r, r, r}, 0x1u, hits, c), 0u);
  EXPECT_GE(hits[0].tri, 0);
  *hit = hits[0];
  const uint32_t mat = g.material[hits[0].tri];
  const HitGeometry<T> h =
      hit_geometry(r, hits[0].t, hits[0].dz, g.normal[hits[0].tri], g.eta_enter[mat],
                   g.eta_leave[mat], T::one(), g.mirror[mat], g.transmit[mat]);
  return {h.p, h.n, h.v, mat};
}

// Snell's law in double for a unit view v and the facing unit normal n, e = n1 / n2.
glm::dvec3 snell(glm::dvec3 v, glm::dvec3 n, double e) {
  const double c = glm::dot(n, v);
  const double q = 1.0 - e * e * (1.0 - c * c);
  return e * v - (e * c + std::sqrt(q)) * n;
}

void expect_near(const std::array<T, 3>& got, glm::dvec3 want, const char* what) {
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[a].to_double(), want[a], 1e-4) << what << " " << a;
}

// Into the glass (the ray meets the pane's front: e = 1 / 1.5) and out of it (the back: e = 1.5),
// each within the format's rounding of Snell's law; the refracted ray is a unit vector.
TEST(GoldenRefract, DirectionFollowsSnellsLaw) {
  const PaneScene s({-5.0}, 0.0, 0.8);
  const uint32_t glass = s.g.material[s.panes[0][0]];
  Hit<T> h;
  const SurfacePoint<T> in = hit_point(s.g, kPaneRay, &h);
  EXPECT_FALSE(lt(T::zero(), h.dz)) << "the front";
  const glm::dvec3 v = glm::normalize(glm::dvec3(1, 0, -1));
  const std::array<T, 3> t_in = refract_dir(in, s.g.eta_enter[glass]);
  expect_near(t_in, snell(v, {0, 0, 1}, 1.0 / 1.5), "entering");
  EXPECT_NEAR(t_in[0].to_double(), std::sin(std::acos(-1.0) / 4) / 1.5, 1e-4) << "sin t";
  // From below, 26.57 degrees from the normal: sin 0.447 x 1.5 = 0.671, it leaves at 42.1.
  const Ray<T> up = ray({0, 0, -7}, {1, 0, 2});
  const SurfacePoint<T> out = hit_point(s.g, up, &h);
  EXPECT_TRUE(lt(T::zero(), h.dz)) << "the back";
  const std::array<T, 3> t_out = refract_dir(out, s.g.eta_leave[glass]);
  expect_near(t_out, snell(glm::normalize(glm::dvec3(1, 0, 2)), {0, 0, -1}, 1.5), "leaving");
  double len2 = 0.0;
  for (const T& x : t_out) len2 += x.to_double() * x.to_double();
  EXPECT_NEAR(len2, 1.0, 1e-4);
}

// Leaving at 45 degrees: sin 0.707 x 1.5 > 1, total internal reflection: the refraction ray takes
// the mirror direction, bit for bit. Straight through (normal incidence) it does not bend.
TEST(GoldenRefract, TotalInternalReflectionTakesTheMirrorDirection) {
  const PaneScene s({-5.0}, 0.0, 0.8);
  const uint32_t glass = s.g.material[s.panes[0][0]];
  Hit<T> h;
  const SurfacePoint<T> out = hit_point(s.g, ray({0, 0, -7}, {1, 0, 1}), &h);
  const std::array<T, 3> t = refract_dir(out, s.g.eta_leave[glass]);
  const std::array<T, 3> m = mirror_dir(out);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(t[a].bits(), m[a].bits()) << a;
  EXPECT_LT(t[2].to_double(), 0.0) << "back down into the glass";
  const SurfacePoint<T> down = hit_point(s.g, ray({0, 0, 0}, {0, 0, -1}), &h);
  expect_near(refract_dir(down, s.g.eta_enter[glass]), {0, 0, -1}, "normal incidence");
}

// The pane (Kd 0, transmit 0.8) shows the floor below it: the floor's ambient term weighted 0.8
// (the pane hides the light from the floor: its shadow ray hits the pane). Without transmit the
// pane is black and sends no ray.
TEST(GoldenRefract, PaneShowsTheFloorBelow) {
  const PaneScene s({-5.0}, 0.0, 0.8);
  const Shaded one = shade_one(s.g, kPaneRay, 3);
  EXPECT_TRUE(one.p.refract_tri[0] == static_cast<int32_t>(s.floor[0]) ||
              one.p.refract_tri[0] == static_cast<int32_t>(s.floor[1]))
      << one.p.refract_tri[0];
  EXPECT_EQ(one.p.bounce_tri[0], -2) << "no mirror";
  EXPECT_EQ(one.c.refract.packets, 1u);
  EXPECT_EQ(one.c.refract.rays, 1u);
  EXPECT_EQ(one.c.bounce.rays, 0u);
  EXPECT_EQ(one.c.shadow.rays, 2u) << "the pane's and the floor's";
  EXPECT_EQ(one.p.lights[0], 1u) << "the light reaches the pane";
  EXPECT_NEAR(one.p.rgb[0][0], byte_of_term(1.0 * kAmbient * 0.8), 1.0);
  EXPECT_GT(one.p.rgb[0][0], 30);
  EXPECT_EQ(one.p.rgb[0][1], 0);
  EXPECT_EQ(one.p.rgb[0][2], 0);
  const PaneScene opaque({-5.0}, 0.0, 0.0);
  const Shaded none = shade_one(opaque.g, kPaneRay, 3);
  EXPECT_EQ(none.p.refract_tri[0], -2);
  EXPECT_EQ(none.c.refract.rays, 0u);
  EXPECT_EQ(none.p.rgb[0][0], 0);
}

// Two panes that reflect and refract (mirror 0.5, transmit 0.5): each hit sends both rays, so
// the tree branches, and mirror and refraction rays share one depth. Depth 1: the pane's mirror
// ray (it leaves the scene) and its refraction ray (to the second pane). Depth 2: the second
// pane's two rays. Depth 3: the mirror ray back up meets the first pane's back, which sends two
// more; the refraction ray meets the opaque floor. So depth d traces d rays of each kind.
TEST(GoldenRefract, TreeBranchesAndSharesTheDepth) {
  const PaneScene s({-5.0, -6.5}, 0.5, 0.5);
  for (uint32_t depth = 0; depth <= 3; ++depth) {
    const Shaded sh = shade_one(s.g, kPaneRay, depth);
    EXPECT_EQ(sh.c.bounce.rays, depth) << "depth " << depth;
    EXPECT_EQ(sh.c.refract.rays, depth) << "depth " << depth;
    EXPECT_EQ(sh.c.bounce.packets, depth);
    EXPECT_EQ(sh.c.refract.packets, depth);
    if (depth > 0) {
      EXPECT_EQ(sh.p.bounce_tri[0], -1) << "the first mirror ray leaves the scene";
      EXPECT_TRUE(sh.p.refract_tri[0] == static_cast<int32_t>(s.panes[1][0]) ||
                  sh.p.refract_tri[0] == static_cast<int32_t>(s.panes[1][1]));
    }
  }
  EXPECT_GT(shade_one(s.g, kPaneRay, 2).p.rgb[0][0], shade_one(s.g, kPaneRay, 1).p.rgb[0][0])
      << "the floor, seen through both panes";
}

// A refraction weight that underflows ends the tree: the first pane's ray has weight 2^-40, the
// second pane's would have 2^-80.
TEST(GoldenRefract, WeightThatUnderflowsEndsTheTree) {
  const PaneScene s({-5.0, -6.5}, 0.0, std::ldexp(1.0, -40));
  const Shaded sh = shade_one(s.g, kPaneRay, 3);
  EXPECT_EQ(sh.c.refract.rays, 1u);
  EXPECT_TRUE(sh.p.refract_tri[0] == static_cast<int32_t>(s.panes[1][0]) ||
              sh.p.refract_tri[0] == static_cast<int32_t>(s.panes[1][1]));
}

}  // namespace
}  // namespace rc::test
