// The reflection rules (docs/architecture.md, "Reflection"), each checked where it decides the
// outcome: a mirror floor that sees a wall (the weighted terms, the mirror ray's hit), a mirror
// ray that leaves the scene (the background's term), two facing mirrors (the bounce depth), a
// weight that underflows; then whole frames: a scene without mirrors renders the same at any
// depth, a scene with mirrors changes only the pixels that have a mirror ray, and the mirror
// rays' first hits agree with Embree's.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "compare.hpp"
#include "embree_engine.hpp"
#include "fp.hpp"
#include "geometry.hpp"
#include "hand_geometry.hpp"
#include "job.hpp"
#include "trace.hpp"

namespace rc::test {
namespace {

using T = fp24;
using scene::KdNode;

const std::string kRoot = RC_SOURCE_DIR;

using hand::add_quad;
using hand::add_tri;
using hand::f;
using hand::ray;
using hand::set_box;

constexpr double kAmbient = static_cast<double>(spec::kShadeAmbientPermille) / 1000.0;

// A term in double as the rules sum it: round(min(max(x, 0), 1) * 2^16).
double fix_d(double x) {
  return std::nearbyint(std::min(std::max(x, 0.0), 1.0) * static_cast<double>(kLightOne));
}
double byte_d(double sum) {
  return std::nearbyint(std::min(sum, static_cast<double>(kLightOne)) * 255.0 /
                        static_cast<double>(kLightOne));
}

// A mirror floor at z = -5 (material 0: grey Kd 0.2, mirror 0.5) and a red wall in the plane
// x = 4 (material 1: Kd (1, 0, 0), no mirror), one leaf, a directional light straight above.
// The ray from (-3, 0, 0) along (1, 0, -1) meets the floor at (2, 0, -5); its mirror ray, along
// (1, 0, 1), meets the wall at (4, 0, -3), inside the wall's first triangle. The light reaches
// the floor (cos = 1) and not the wall (cos = 0).
struct MirrorScene {
  Geometry<T> g;
  std::array<uint32_t, 2> floor;
  uint32_t wall0 = 0, wall1 = 0;
  explicit MirrorScene(double mirror = 0.5) {
    floor = add_quad(g, -4, 4, -4, 4, -5);
    wall0 = add_tri(g, {4, -4, -5}, {4, 4, -5}, {4, -4, 5});
    wall1 = add_tri(g, {4, 4, -5}, {4, 4, 5}, {4, -4, 5});
    g.material[wall0] = g.material[wall1] = 1;
    g.kd = {{f(0.2), f(0.2), f(0.2)}, {f(1.0), f(0.0), f(0.0)}};
    g.ks = {{f(0.0), f(0.0), f(0.0)}, {f(0.0), f(0.0), f(0.0)}};
    g.ns = {0, 0};
    g.mirror = {f(mirror), f(0.0)};
    g.transmit = {f(0.0), f(0.0)};
    g.eta_enter = g.eta_leave = {f(1.0), f(1.0)};
    g.nodes = {KdNode::leaf(0, 4).raw};
    g.lists = {floor[0], floor[1], wall0, wall1};
    set_box(g, -8, 8);
    g.t_eps = f(16.0 * std::sqrt(3.0) / 4096.0);
    Geometry<T>::Light l;
    l.directional = true;
    l.pos = {f(0.0), f(0.0), f(1.0)};
    l.color = {f(1.0), f(1.0), f(1.0)};
    g.lights = {l};
  }
};

const Ray<T> kFloorRay = ray({-3, 0, 0}, {1, 0, -1});

struct Shaded {
  LitPacket p;
  Counters primary, shadow, bounce, refract;
};

Shaded shade_one(const Geometry<T>& g, const Ray<T>& r, uint32_t max_bounces,
                 std::array<uint8_t, 3> background = {0, 0, 0}) {
  Shaded s;
  std::array<Hit<T>, kPacketRays> hits;
  EXPECT_EQ(trace_packet(g, {r, r, r, r}, 0x1u, hits, s.primary), 0u);
  LitCounters lc;
  s.p = shade_lit(g, {r, r, r, r}, 0x1u, hits, lit_params<T>(max_bounces, background), lc);
  s.shadow = lc.shadow;
  s.bounce = lc.bounce;
  s.refract = lc.refract;
  return s;
}

// The floor's own terms (ambient, the light at cos = 1) plus the wall's ambient term seen through
// the mirror, weighted 0.5: red 0.04 + 0.2 + 0.1, green and blue 0.04 + 0.2. Checked against the
// sums in double (each term within the format's rounding: one byte).
TEST(GoldenReflect, MirrorFloorSeesTheWall) {
  const MirrorScene s;
  const Shaded one = shade_one(s.g, kFloorRay, 3);
  EXPECT_EQ(one.p.bounce_tri[0], static_cast<int32_t>(s.wall0));
  EXPECT_EQ(one.p.lights[0], 1u) << "the light reaches the floor";
  const double floor_terms = fix_d(0.2 * kAmbient) + fix_d(0.2);
  EXPECT_NEAR(one.p.rgb[0][0], byte_d(floor_terms + fix_d(1.0 * kAmbient * 0.5)), 1.0);
  EXPECT_NEAR(one.p.rgb[0][1], byte_d(floor_terms), 1.0);
  EXPECT_NEAR(one.p.rgb[0][2], byte_d(floor_terms), 1.0);
  EXPECT_GT(one.p.rgb[0][0], one.p.rgb[0][1] + 20) << "the wall's red, through the mirror";
  // One mirror ray in one packet; its hit (the wall) faces away from the light: no shadow ray.
  EXPECT_EQ(one.bounce.packets, 1u);
  EXPECT_EQ(one.bounce.rays, 1u);
  EXPECT_EQ(one.shadow.rays, 1u) << "the floor's shadow ray only";

  // Depth 0: no mirror ray, the floor's own terms only.
  const Shaded none = shade_one(s.g, kFloorRay, 0);
  EXPECT_EQ(none.p.bounce_tri[0], -2);
  EXPECT_EQ(none.bounce.rays, 0u);
  EXPECT_EQ(none.p.rgb[0][0], none.p.rgb[0][1]);
  EXPECT_NEAR(none.p.rgb[0][0], byte_d(floor_terms), 1.0);
  // A material without mirror sends none either.
  const MirrorScene dull(0.0);
  const Shaded d = shade_one(dull.g, kFloorRay, 3);
  EXPECT_EQ(d.p.bounce_tri[0], -2);
  EXPECT_EQ(d.p.rgb[0], none.p.rgb[0]);
}

// The mirror ray starts on the floor; the start triangle's exclusion and t_eps keep it off the
// floor even though it starts in the floor's plane (after rounding, possibly a little below).
// Pointing the ray away from the wall, it leaves the scene and sees the background, weighted:
// red background 255 adds fix(1.0 * 0.5).
TEST(GoldenReflect, MirrorRayThatLeavesSeesTheBackground) {
  const MirrorScene s;
  const Ray<T> away = ray({3, 0, 0}, {-1, 0, -1});  // meets the floor at (-2, 0, -5), goes -x
  const Shaded black = shade_one(s.g, away, 3);
  EXPECT_EQ(black.p.bounce_tri[0], -1) << "the mirror ray misses";
  const Shaded red = shade_one(s.g, away, 3, {255, 0, 0});
  EXPECT_EQ(red.p.bounce_tri[0], -1);
  const double floor_terms = fix_d(0.2 * kAmbient) + fix_d(0.2);
  EXPECT_NEAR(red.p.rgb[0][0], byte_d(floor_terms + fix_d(0.5)), 1.0);
  EXPECT_EQ(red.p.rgb[0][1], black.p.rgb[0][1]);
  EXPECT_EQ(black.p.rgb[0][0], black.p.rgb[0][1]);
}

// Two facing mirrors (a floor at z = -5 facing up, a ceiling at z = 5 facing down, both mirror
// 0.5): a slanted ray bounces between them for as long as the depth allows. Each level is one
// packet of one mirror ray.
TEST(GoldenReflect, FacingMirrorsStopAtTheBounceDepth) {
  Geometry<T> g;
  const auto floor = add_quad(g, -8, 8, -8, 8, -5);
  const auto ceiling = add_quad(g, -8, 8, -8, 8, 5);
  g.kd = {{f(0.1), f(0.1), f(0.1)}};
  g.ks = {{f(0.0), f(0.0), f(0.0)}};
  g.ns = {0};
  g.mirror = {f(0.5)};
  g.transmit = {f(0.0)};
  g.eta_enter = g.eta_leave = {f(1.0)};
  g.nodes = {KdNode::leaf(0, 4).raw};
  g.lists = {floor[0], floor[1], ceiling[0], ceiling[1]};
  set_box(g, -8, 8);
  g.t_eps = f(16.0 * std::sqrt(3.0) / 4096.0);
  Geometry<T>::Light l;
  l.pos = {f(0.0), f(0.0), f(0.0)};  // a point light between the mirrors
  l.color = {f(0.5), f(0.5), f(0.5)};
  g.lights = {l};
  const Ray<T> r = ray({-4, 0, 0}, {0.25, 0, -1});
  uint32_t last_rgb = 0;
  for (uint32_t depth = 0; depth <= 4; ++depth) {
    const Shaded s = shade_one(g, r, depth);
    EXPECT_EQ(s.bounce.rays, depth) << "depth " << depth;
    EXPECT_EQ(s.bounce.packets, depth);
    EXPECT_EQ(s.shadow.rays, depth + 1) << "every hit sees the light";
    if (depth > 0) {
      EXPECT_EQ(s.p.bounce_tri[0] == static_cast<int32_t>(ceiling[0]) ||
                    s.p.bounce_tri[0] == static_cast<int32_t>(ceiling[1]),
                true);
      EXPECT_GE(s.p.rgb[0][0], last_rgb) << "each level adds its terms";
    }
    last_rgb = s.p.rgb[0][0];
  }
}

// The weight is the product of the mirrors' weights along the way: when it underflows to 0 the
// next mirror ray is not traced.
TEST(GoldenReflect, WeightThatUnderflowsEndsTheTree) {
  MirrorScene s(std::ldexp(1.0, -40));
  // The floor sees the wall with weight 2^-40 (> 0): one mirror ray. Make the wall a mirror of
  // the same weight: its mirror ray would have weight 2^-80, below the format's range.
  s.g.mirror[1] = f(std::ldexp(1.0, -40));
  ASSERT_GT(s.g.mirror[1].to_double(), 0.0);
  ASSERT_EQ((s.g.mirror[0] * s.g.mirror[1]).to_double(), 0.0);
  const Shaded sh = shade_one(s.g, kFloorRay, 3);
  EXPECT_EQ(sh.bounce.rays, 1u);
  EXPECT_EQ(sh.p.bounce_tri[0], static_cast<int32_t>(s.wall0));
}

RenderInput load(const std::string& input) {
  return load_render_input(input, scene::LoadOptions{}, scene::NumberFormat::fp24());
}

Frame lit_frame(const Geometry<T>& g, const RenderInput& in, uint32_t bounces) {
  RenderOptions opt = input_options(in);
  opt.width = 96;
  opt.height = 72;
  opt.progress = false;
  opt.lighting = Lighting::kScene;
  opt.max_bounces = bounces;
  return render_golden(g, opt);
}

// A scene without mirrors renders the same at every depth (a mirror term is only ever added to
// the pixels that have a mirror ray); the default scene has none.
TEST(GoldenReflect, SceneWithoutMirrorsIsTheSameAtAnyDepth) {
  const RenderInput in = load(kRoot + "/scenes/default.json");
  const Geometry<T> g = load_geometry<T>(in.image);
  const Frame f0 = lit_frame(g, in, 0), f3 = lit_frame(g, in, 3);
  EXPECT_EQ(f3.rgb, f0.rgb);
  EXPECT_EQ(f3.light_mask, f0.light_mask);
  EXPECT_EQ(f3.bounce_counters.rays, 0u);
  for (int32_t t : f3.bounce_tri) ASSERT_EQ(t, -2);
}

// The spheres scene has mirror spheres, glass spheres and a mirror ground: at depth 3, every
// pixel without a mirror or refraction ray keeps its depth-0 colour, and the pixels with one
// change; the mirror and refraction rays' first hits agree with Embree's.
TEST(GoldenReflect, SpheresScene) {
  const RenderInput in = load(kRoot + "/scenes/spheres.json");
  const Geometry<T> g = load_geometry<T>(in.image);
  const Frame f0 = lit_frame(g, in, 0), f3 = lit_frame(g, in, 3);
  uint64_t with_ray = 0, changed = 0, with_refraction = 0;
  for (size_t p = 0; p < f3.bounce_tri.size(); ++p) {
    with_refraction += f3.refract_tri[p] != -2;
    if (f3.bounce_tri[p] == -2 && f3.refract_tri[p] == -2) {
      ASSERT_EQ(f3.rgb[3 * p], f0.rgb[3 * p]) << "pixel " << p;
      ASSERT_EQ(f3.rgb[3 * p + 1], f0.rgb[3 * p + 1]) << "pixel " << p;
      ASSERT_EQ(f3.rgb[3 * p + 2], f0.rgb[3 * p + 2]) << "pixel " << p;
      continue;
    }
    ++with_ray;
    changed += f3.rgb[3 * p] != f0.rgb[3 * p] || f3.rgb[3 * p + 1] != f0.rgb[3 * p + 1] ||
               f3.rgb[3 * p + 2] != f0.rgb[3 * p + 2];
  }
  EXPECT_GT(with_ray, 100u);
  EXPECT_GT(changed, with_ray / 2);
  EXPECT_EQ(f3.bounce_counters.errors, 0u);
  EXPECT_GE(f3.bounce_counters.rays + f3.refract_counters.rays, with_ray)
      << "first mirror and refraction rays, and deeper ones";
  EXPECT_EQ(f0.bounce_counters.rays, 0u);

  RenderOptions opt = input_options(in);
  opt.width = 96;
  opt.height = 72;
  opt.progress = false;
  opt.lighting = Lighting::kScene;
  opt.max_bounces = 3;
  const Frame e = render_embree<T>(triangle_soup(*in.scene), opt, soup_lights(*in.scene));
  const BounceAgreement ba = compare_bounces(f3, e);
  std::printf(
      "[reflect agreement] spheres at 96x72: first mirror ray %.4f%% of %llu agree on the "
      "triangle hit (%llu traced by one engine only)\n",
      100.0 * ba.share(), static_cast<unsigned long long>(ba.rays),
      static_cast<unsigned long long>(ba.only_one));
  EXPECT_GT(ba.rays, with_ray / 2);
  EXPECT_GE(ba.share(), 0.99);
  const BounceAgreement ra = compare_refractions(f3, e);
  std::printf(
      "[refract agreement] spheres at 96x72: first refraction ray %.4f%% of %llu agree on the "
      "triangle hit (%llu traced by one engine only)\n",
      100.0 * ra.share(), static_cast<unsigned long long>(ra.rays),
      static_cast<unsigned long long>(ra.only_one));
  EXPECT_GT(with_refraction, 50u) << "the glass spheres";
  EXPECT_GT(ra.rays, with_refraction / 2);
  EXPECT_GE(ra.share(), 0.99);
  EXPECT_EQ(f3.refract_counters.errors, 0u);
  EXPECT_EQ(f0.refract_counters.rays, 0u);
}

// A scene without transparent materials (the Cornell box with its mirror block) traces no
// refraction ray.
TEST(GoldenReflect, SceneWithoutGlassTracesNoRefraction) {
  const RenderInput in = load(kRoot + "/scenes/cornell-mirror.json");
  const Frame f3 = lit_frame(load_geometry<T>(in.image), in, 3);
  EXPECT_GT(f3.bounce_counters.rays, 0u);
  EXPECT_EQ(f3.refract_counters.rays, 0u);
  for (int32_t t : f3.refract_tri) ASSERT_EQ(t, -2);
}

}  // namespace
}  // namespace rc::test
