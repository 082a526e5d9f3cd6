// The kd-tree is sound: every triangle is listed by every leaf its geometry overlaps (leaf boxes
// rebuilt from the stored split values), nodes are well formed, every node is reached once, the
// depth is within the limit and the reported SAH cost matches the image.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <random>

#include "compiler.hpp"
#include "error.hpp"
#include "fp.hpp"
#include "test_util.hpp"

namespace rc::test {
namespace {

using rc::scene::Compiled;
using rc::scene::CompileOptions;
using rc::scene::Mesh;
using rc::scene::NumberFormat;
using rc::scene::Scene;
using rc::scene::SceneImage;

Scene mesh_scene(Mesh mesh) {
  Scene s;
  s.name = mesh.source;
  s.source = mesh.source;
  mesh.material.assign(mesh.triangles.size(), 0);
  mesh.line.assign(mesh.triangles.size(), 0);
  mesh.materials.resize(1);
  s.meshes.push_back(std::move(mesh));
  return s;
}

// Compiles, reads back, validates and checks soundness; returns the check.
TreeCheck compile_and_check(const Scene& scene, const CompileOptions& opt,
                            const std::string& what) {
  const Compiled c = rc::scene::compile_scene(scene, opt);
  const SceneImage img = SceneImage::from_bytes(c.image, what);
  const auto problems = img.validate();
  for (const auto& p : problems) ADD_FAILURE() << what << ": " << p;
  const TreeCheck t = check_tree(img, scene_triangles(scene));
  report_cases(what + " (triangle, overlapped leaf) pairs listed", t.pairs, t.missing);
  for (const auto& p : t.problems) ADD_FAILURE() << what << ": " << p;
  EXPECT_EQ(t.missing, 0u) << what;
  EXPECT_EQ(t.unsorted, 0u) << what;
  EXPECT_EQ(t.nodes, img.node_count()) << what << ": every node reached once";
  EXPECT_EQ(t.depth, img.tree_depth()) << what;
  EXPECT_LE(t.depth, static_cast<uint32_t>(opt.kd.max_depth)) << what;
  EXPECT_NEAR(t.sah, c.stats.sah_cost, 1e-9 * std::max(1.0, t.sah)) << what;
  return t;
}

class BuiltinScene : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinScene, TreeIsSound) {
  const Scene scene = rc::scene::builtin_scene(GetParam());
  compile_and_check(scene, CompileOptions(), "builtin:" + GetParam() + " fp24");
}

INSTANTIATE_TEST_SUITE_P(Scenes, BuiltinScene, ::testing::Values("cornell", "spheres", "terrain"));

class BuiltinSceneFp32 : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinSceneFp32, TreeIsSound) {
  CompileOptions opt;
  opt.format = NumberFormat::fp32();
  compile_and_check(rc::scene::builtin_scene(GetParam()), opt, "builtin:" + GetParam() + " fp32");
}

// The terrain is left to the fp24 test (it is the slowest check); the random soups cover fp32 too.
INSTANTIATE_TEST_SUITE_P(Scenes, BuiltinSceneFp32, ::testing::Values("cornell", "spheres"));

// Random triangle soups built to provoke the corner cases: vertices on the format's grid (so that
// split candidates coincide with vertex coordinates), axis-aligned planar triangles, shared
// vertices, long thin triangles crossing many cells, and clusters far apart.
Mesh random_soup(uint64_t seed, size_t count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mesh m;
  m.source = "soup" + std::to_string(seed);
  const auto grid = [&](double x) { return rc::fp24::from_double(x).to_double(); };
  for (size_t i = 0; i < count; ++i) {
    const int kind = static_cast<int>(rng() % 5);
    glm::dvec3 c(u(rng) * 10, u(rng) * 10, u(rng) * 10);
    if (i % 7 == 0) c += glm::dvec3(100, 0, 0);  // a far cluster
    std::array<glm::dvec3, 3> v;
    for (auto& p : v) p = c + glm::dvec3(u(rng), u(rng), u(rng)) * (kind == 4 ? 8.0 : 0.5);
    if (kind == 1)
      for (auto& p : v) p = {grid(p.x), grid(p.y), grid(p.z)};
    if (kind == 2) {
      const int a = static_cast<int>(rng() % 3);
      for (auto& p : v) p[a] = grid(c[a]);
    }
    const uint32_t base = static_cast<uint32_t>(m.vertices.size());
    for (const auto& p : v) m.vertices.push_back(p);
    if (kind == 3 && base >= 3) {
      m.triangles.push_back({base - 3, base, base + 1});  // shares a vertex with the previous one
    } else {
      m.triangles.push_back({base, base + 1, base + 2});
    }
  }
  return m;
}

TEST(KdTree, RandomSoupsAreSound) {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    for (const NumberFormat f : {NumberFormat::fp24(), NumberFormat::fp32()}) {
      CompileOptions opt;
      opt.format = f;
      compile_and_check(mesh_scene(random_soup(seed, 300 * seed)), opt,
                        "soup " + std::to_string(seed) + " " + f.name());
    }
  }
}

TEST(KdTree, AxisAlignedBoxesAreSound) {
  // Cubes whose faces lie on split candidates of each other: many planar triangles in planes that
  // are node faces.
  Mesh m;
  m.source = "cubes";
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const glm::dvec3 lo(i * 1.5, (i + j) % 3 * 0.5, j * 1.5),
          hi = lo + glm::dvec3(1.0 + 0.25 * i);
      const auto idx = [&](int k) {
        m.vertices.push_back({(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z});
        return static_cast<uint32_t>(m.vertices.size() - 1);
      };
      uint32_t c[8];
      for (int k = 0; k < 8; ++k) c[k] = idx(k);
      const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                               {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
      for (const auto& f : faces) {
        m.triangles.push_back({c[f[0]], c[f[1]], c[f[2]]});
        m.triangles.push_back({c[f[0]], c[f[2]], c[f[3]]});
      }
    }
  compile_and_check(mesh_scene(m), CompileOptions(), "axis-aligned cubes");
}

TEST(KdTree, DepthLimitIsRespected) {
  CompileOptions opt;
  opt.kd.max_depth = 3;
  const TreeCheck t =
      compile_and_check(rc::scene::builtin_scene("spheres"), opt, "spheres depth 3");
  EXPECT_EQ(t.depth, 3u);
}

TEST(KdTree, EmptySpaceBetweenClustersIsCut) {
  Mesh m;
  m.source = "two clusters";
  for (int c = 0; c < 2; ++c)
    for (int i = 0; i < 20; ++i) {
      const double x = c * 1000.0 + i * 0.1;
      const uint32_t b = static_cast<uint32_t>(m.vertices.size());
      m.vertices.push_back({x, 0, 0});
      m.vertices.push_back({x + 0.05, 1, 0});
      m.vertices.push_back({x, 0, 1});
      m.triangles.push_back({b, b + 1, b + 2});
    }
  const Compiled c = rc::scene::compile_scene(mesh_scene(m), CompileOptions());
  const SceneImage img = SceneImage::from_bytes(c.image);
  const auto root = img.node(0);
  ASSERT_FALSE(root.is_leaf());
  EXPECT_EQ(root.axis(), 0);
  const double s = img.format().decode(root.split_bits());
  EXPECT_GT(s, 1.95);  // the first cluster ends at x = 1.95, the second starts at 1000
  EXPECT_LT(s, 1000.0);
}

TEST(KdTree, SplitValuesAreFormatValues) {
  // Every split decodes to a value that the format represents exactly, strictly inside its box
  // (validate() checks the box), and is stored as +0 rather than -0.
  for (const NumberFormat f : {NumberFormat::fp24(), NumberFormat::fp32()}) {
    CompileOptions opt;
    opt.format = f;
    const Compiled c = rc::scene::compile_scene(rc::scene::builtin_scene("spheres"), opt);
    const SceneImage img = SceneImage::from_bytes(c.image);
    size_t cases = 0, bad = 0;
    for (size_t i = 0; i < img.node_count(); ++i) {
      const auto n = img.node(i);
      if (n.is_leaf()) continue;
      ++cases;
      const double s = f.decode(n.split_bits());
      bad += f.encode(s) != n.split_bits() || !f.finite_bits(n.split_bits());
    }
    report_cases("split values round-trip " + f.name(), cases, bad);
    EXPECT_EQ(bad, 0u);
  }
}

// M maps A, B, C and A + n to the unit triangle's corners; the stored values are the double
// results rounded once (encode of the double value); an independent inverse agrees to an ulp.
TEST(Transform, UnitTriangleTransform) {
  const Scene scene = mesh_scene(random_soup(42, 2000));
  for (const NumberFormat f : {NumberFormat::fp24(), NumberFormat::fp32()}) {
    CompileOptions opt;
    opt.format = f;
    const Compiled c = rc::scene::compile_scene(scene, opt);
    const SceneImage img = SceneImage::from_bytes(c.image);
    const auto tris = scene_triangles(scene);
    const double eps = std::ldexp(1.0, -f.frac_w());
    size_t cases = 0, bad = 0;
    for (size_t t = 0; t < tris.size(); ++t) {
      if (img.triangle_dropped(t)) continue;
      const auto& [a, b, cc] = tris[t];
      std::array<double, 12> m{};
      ASSERT_TRUE(rc::scene::unit_triangle_transform(a, b, cc, &m));
      const auto bits = img.triangle_bits(t);
      const auto vals = img.triangle_values(t);
      // Rounded once.
      for (int k = 0; k < 12; ++k) {
        ++cases;
        bad += bits[k] != f.encode(m[k]);
      }
      // Independent inverse (the 4x4 matrix with columns e1, e2, n, A).
      const glm::dvec3 e1 = b - a, e2 = cc - a, n = glm::cross(e1, e2);
      const glm::dmat4 fwd(glm::dvec4(e1, 0), glm::dvec4(e2, 0), glm::dvec4(n, 0),
                           glm::dvec4(a, 1));
      const glm::dmat4 inv = glm::inverse(fwd);
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 4; ++k) {
          const double want = inv[k][r];
          ++cases;
          bad += std::abs(vals[4 * r + k] - want) > 2 * eps * std::abs(want) + f.next_up(0.0);
        }
      // The mapping, evaluated in double with the stored values.
      const glm::dvec3 pts[4] = {a, b, cc, a + n};
      const glm::dvec3 want[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
      for (int p = 0; p < 4; ++p)
        for (int r = 0; r < 3; ++r) {
          double got = vals[4 * r + 3], mag = std::abs(vals[4 * r + 3]);
          for (int k = 0; k < 3; ++k) {
            got += vals[4 * r + k] * pts[p][k];
            mag += std::abs(vals[4 * r + k] * pts[p][k]);
          }
          ++cases;
          bad += std::abs(got - want[p][r]) > 4 * eps * mag + 1e-12;
        }
    }
    report_cases("unit-triangle transforms " + f.name(), cases, bad);
    EXPECT_EQ(bad, 0u);
  }
}

TEST(Transform, DegenerateTrianglesAreDroppedAndCounted) {
  Mesh m;
  m.source = "degenerates";
  m.vertices = {{0, 0, 0}, {1, 0, 0},     {0, 1, 0},      // 0: fine
                {0, 0, 0}, {1, 1, 1},     {2, 2, 2},      // 1: collinear
                {5, 5, 5}, {5, 5, 5},     {6, 5, 5},      // 2: repeated vertex
                {0, 0, 0}, {1e-12, 0, 0}, {0, 1e-12, 0},  // 3: transform overflows fp24
                {3, 0, 0}, {4, 0, 0},     {3, 1, 1}};     // 4: fine
  for (uint32_t i = 0; i < 5; ++i) m.triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  const Scene scene = mesh_scene(m);
  const Compiled c = rc::scene::compile_scene(scene, CompileOptions());
  EXPECT_EQ(c.stats.dropped, 3u);
  const SceneImage img = SceneImage::from_bytes(c.image);
  EXPECT_EQ(img.dropped_count(), 3u);
  EXPECT_EQ(img.triangle_count(), 5u);
  for (size_t t : {1, 2, 3}) {
    EXPECT_TRUE(img.triangle_dropped(t)) << t;
    for (uint32_t b : img.triangle_bits(t)) EXPECT_EQ(b, 0u);
  }
  for (size_t t : {0, 4}) EXPECT_FALSE(img.triangle_dropped(t)) << t;
  for (size_t i = 0; i < img.list_size(); ++i) {
    const uint32_t t = img.list_entry(i);
    EXPECT_TRUE(t == 0 || t == 4) << "list entry names dropped triangle " << t;
  }
  EXPECT_TRUE(img.validate().empty());
  // At fp32 the tiny triangle's transform fits: only two are dropped.
  CompileOptions fp32;
  fp32.format = NumberFormat::fp32();
  EXPECT_EQ(rc::scene::compile_scene(scene, fp32).stats.dropped, 2u);
}

}  // namespace
}  // namespace rc::test
