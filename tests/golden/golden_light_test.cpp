// The lighting rules (docs/architecture.md, "Lighting"), each checked where it decides the
// outcome: a floor point in an occluder's shadow and one beside it, a light behind the surface, a
// directional light, the start triangle's exclusion, any-hit termination, the fixed-point sums and
// the exponent; then whole frames: a scene without lights keeps the headlight, lit frames are the
// same at any thread count, and the shadow test agrees with Embree's.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <limits>
#include <string>
#include <vector>

#include "compare.hpp"
#include "compiler.hpp"
#include "embree_engine.hpp"
#include "fp.hpp"
#include "geometry.hpp"
#include "hand_geometry.hpp"
#include "image.hpp"
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

void set_material(Geometry<T>& g, double kd, double ks, uint32_t ns) {
  g.kd = {{f(kd), f(kd), f(kd)}};
  g.ks = {{f(ks), f(ks), f(ks)}};
  g.ns = {ns};
  g.mirror = {f(0.0)};
  g.transmit = {f(0.0)};
  g.eta_enter = g.eta_leave = {f(1.0)};
}

Geometry<T>::Light point_light(glm::dvec3 p, double intensity) {
  Geometry<T>::Light l;
  l.pos = {f(p.x), f(p.y), f(p.z)};
  l.color = {f(intensity), f(intensity), f(intensity)};
  return l;
}

// A floor at z = -5 (x, y in [-4, 4]) and an occluder at z = -3 (x in [1, 2]), one leaf; a point
// light at (4, 0, -1). Seen straight down from z = 0, the floor point at x = -1 is in the
// occluder's shadow (its segment to the light crosses z = -3 at x = 1.5) and the one at x = -3 is
// not (x = 0.5 there); neither primary ray meets the occluder.
struct ShadowScene {
  Geometry<T> g;
  std::array<uint32_t, 2> floor, occluder;
  ShadowScene() {
    floor = add_quad(g, -4, 4, -4, 4, -5);
    occluder = add_quad(g, 1, 2, -4, 4, -3);
    g.nodes = {KdNode::leaf(0, 4).raw};
    g.lists = {floor[0], floor[1], occluder[0], occluder[1]};
    set_box(g, -8, 8);
    g.t_eps = f(16.0 * std::sqrt(3.0) / 4096.0);
    set_material(g, 0.5, 0.0, 0);
    g.lights = {point_light({4, 0, -1}, 1.0)};
  }
};

LitPacket shade_rays(const Geometry<T>& g, const std::array<Ray<T>, kPacketRays>& rays,
                     uint32_t mask, Counters& primary, Counters& shadow) {
  std::array<Hit<T>, kPacketRays> hits;
  EXPECT_EQ(trace_packet(g, rays, mask, hits, primary), 0u);
  LitCounters lc;
  const LitPacket p = shade_lit(g, rays, mask, hits, LitParams<T>{}, lc);
  shadow.add(lc.shadow);
  EXPECT_EQ(lc.bounce.rays, 0u) << "no mirror materials here";
  EXPECT_EQ(lc.refract.rays, 0u) << "no transparent materials here";
  return p;
}

TEST(GoldenLight, OccludedPointGetsOnlyTheAmbientTerm) {
  const ShadowScene s;
  Counters pc, sc;
  const Ray<T> shadowed = ray({-1, 0, 0}, {0, 0, -1}), lit = ray({-3, 0, 0}, {0, 0, -1});
  const LitPacket p = shade_rays(s.g, {shadowed, lit, shadowed, lit}, 0x3u, pc, sc);
  EXPECT_EQ(p.lights[0], 0u) << "the occluder hides the light";
  EXPECT_EQ(p.lights[1], 1u) << "the light reaches x = -3";
  // The ambient term alone: Kd * ambient = 0.5 * 0.2 = 0.1 -> 6554 / 65536 -> 25.5 -> 26 (0.1
  // rounds up in the format, so the tie does not arise).
  const uint32_t amb = light_fixed(f(0.5) * shade_ambient<T>());
  for (int c = 0; c < 3; ++c) EXPECT_EQ(p.rgb[0][c], light_byte(amb));
  EXPECT_GT(p.rgb[1][0], p.rgb[0][0]);
  // One shadow packet of two rays: both rays face the light.
  EXPECT_EQ(sc.packets, 1u);
  EXPECT_EQ(sc.rays, 2u);
  EXPECT_EQ(sc.errors, 0u);
}

// The lit point's colour, term by term in double: Kd * cos with cos = n . l (n = +z, l toward
// (4, 0, -1) from (-3, 0, -5)), within the format's rounding.
TEST(GoldenLight, LitPointIsAmbientPlusDiffuse) {
  const ShadowScene s;
  Counters pc, sc;
  const Ray<T> lit = ray({-3, 0, 0}, {0, 0, -1});
  const LitPacket p = shade_rays(s.g, {lit, lit, lit, lit}, 0x1u, pc, sc);
  const glm::dvec3 l = glm::normalize(glm::dvec3(4, 0, -1) - glm::dvec3(-3, 0, -5));
  const double want = (0.5 * 0.2 + 0.5 * l.z) * 255.0;
  EXPECT_NEAR(p.rgb[0][0], want, 1.0);
}

TEST(GoldenLight, LightBehindTheSurfaceSendsNoRay) {
  ShadowScene s;
  s.g.lights = {point_light({0, 0, -9}, 1.0)};  // below the floor
  Counters pc, sc;
  const Ray<T> r = ray({-3, 0, 0}, {0, 0, -1});
  const LitPacket p = shade_rays(s.g, {r, r, r, r}, 0x1u, pc, sc);
  EXPECT_EQ(p.lights[0], 0u);
  EXPECT_EQ(sc.packets, 0u) << "no ray faces the light: no shadow packet";
}

TEST(GoldenLight, BackFaceUsesTheFacingNormal) {
  ShadowScene s;
  s.g.lights = {point_light({-3, 0, -9}, 1.0)};
  Counters pc, sc;
  // From below, the floor's back: the facing normal is -z, and the light below reaches it.
  const Ray<T> r = ray({-3, 0, -8}, {0, 0, 1});
  const LitPacket p = shade_rays(s.g, {r, r, r, r}, 0x1u, pc, sc);
  EXPECT_EQ(p.lights[0], 1u);
  EXPECT_EQ(sc.packets, 1u);
}

TEST(GoldenLight, DirectionalLight) {
  ShadowScene s;
  Geometry<T>::Light l;
  l.directional = true;
  const glm::dvec3 toward = glm::normalize(glm::dvec3(1, 0, 1));  // travels along (-1, 0, -1)
  l.pos = {f(toward.x), f(toward.y), f(toward.z)};
  l.color = {f(1), f(1), f(1)};
  s.g.lights = {l};
  Counters pc, sc;
  // x = -0.5: toward the light, the ray meets z = -3 at x = 1.5, in the occluder; x = -3: at -1.
  const Ray<T> shadowed = ray({-0.5, 0, 0}, {0, 0, -1}), lit = ray({-3, 0, 0}, {0, 0, -1});
  const LitPacket p = shade_rays(s.g, {shadowed, lit, lit, lit}, 0x3u, pc, sc);
  EXPECT_EQ(p.lights[0], 0u);
  EXPECT_EQ(p.lights[1], 1u);
}

// A shadow ray starts on its own triangle, possibly (after rounding) a little behind it. The
// exclusion keeps its own triangle out at any distance; t_eps keeps out a neighbour in the same
// plane (here floor[1], beside floor[0]) that the ray meets right at its start. Each is checked
// against the ray without it, which does hit.
TEST(GoldenLight, StartTriangleNeverOccludes) {
  const ShadowScene s;
  const auto shadow_hit = [&](glm::dvec3 o, T t_lo, int32_t exclude) {
    SecondaryLimits<T> lim;
    lim.t_lo = t_lo;
    lim.exclude = {exclude, -1, -1, -1};
    lim.t_hi = {f(10), f(10), f(10), f(10)};
    const Ray<T> r = ray(o, {0, 0, 1});  // straight up, away from the floor
    std::array<Hit<T>, kPacketRays> hits;
    Counters c;
    EXPECT_EQ(trace_packet(s.g, {r, r, r, r}, 0x1u, hits, c, &lim), 0u);
    return hits[0].tri;
  };
  const int32_t own = static_cast<int32_t>(s.floor[0]);
  const double eps = s.g.t_eps.to_double();
  // (-3, 0) lies on floor[0] (x + y < 0). 10 t_eps below it: only the exclusion helps.
  EXPECT_EQ(shadow_hit({-3, 0, -5 - 10 * eps}, s.g.t_eps, own), -1);
  EXPECT_EQ(shadow_hit({-3, 0, -5 - 10 * eps}, s.g.t_eps, -1), own);
  for (double z : {-5.0, -5.0 - eps / 2, -5.0 + eps / 2})
    EXPECT_EQ(shadow_hit({-3, 0, z}, s.g.t_eps, own), -1) << "z = " << z;
  // (0.5, 0.5) lies on floor[1]; half a t_eps below it, the ray meets floor[1] at t = t_eps / 2.
  EXPECT_EQ(shadow_hit({0.5, 0.5, -5 - eps / 2}, s.g.t_eps, own), -1);
  EXPECT_EQ(shadow_hit({0.5, 0.5, -5 - eps / 2}, T::zero(), own), static_cast<int32_t>(s.floor[1]));
}

// Only hits before the light occlude: an occluder beyond a point light does not.
TEST(GoldenLight, OccluderBeyondThePointLightDoesNotShadow) {
  ShadowScene s;
  s.g.lights = {point_light({1.5, 0, -4}, 1.0)};  // between the floor and the occluder
  Counters pc, sc;
  const Ray<T> r = ray({-1, 0, 0}, {0, 0, -1});
  const LitPacket p = shade_rays(s.g, {r, r, r, r}, 0x1u, pc, sc);
  EXPECT_EQ(p.lights[0], 1u);
}

// Two leaves: the root splits x at 0; the left leaf lists a square at z = -5 and the right one a
// square at z = -3, both spanning x in [-1, 1]. The ray from (-0.5, 0.25, 0) along
// (0.125, 0, -1) meets the left square at t = 5 inside the left leaf and crosses into the right
// leaf at t = 4.
Geometry<T> two_leaves() {
  Geometry<T> g;
  const auto left = add_quad(g, -1, 1, -1, 1, -5);
  const auto right = add_quad(g, -1, 1, -1, 1, -3);
  g.nodes = {KdNode::inner(0, 1, f(0.0).bits()).raw, KdNode::leaf(0, 2).raw,
             KdNode::leaf(2, 2).raw};
  g.lists = {left[0], left[1], right[0], right[1]};
  set_box(g, -8, 8);
  return g;
}
const Ray<T> kTwoLeavesRay = ray({-0.5, 0.25, 0}, {0.125, 0, -1});

// Any-hit: the ray crosses into the right leaf at t = 4 <= 5, so the closest-hit rule visits
// both leaves (and finds t = 3); a shadow ray stops after the first.
TEST(GoldenLight, ShadowRayEndsAtTheFirstOccluder) {
  const Geometry<T> g = two_leaves();
  const Ray<T> r = kTwoLeavesRay;
  std::array<Hit<T>, kPacketRays> hits;
  Counters closest;
  ASSERT_EQ(trace_packet(g, {r, r, r, r}, 0x1u, hits, closest), 0u);
  EXPECT_EQ(closest.leaf_visits, 2u);
  EXPECT_EQ(hits[0].t.to_double(), 3.0);
  SecondaryLimits<T> lim;
  lim.t_lo = f(1e-3);
  lim.t_hi = {T::inf(), T::inf(), T::inf(), T::inf()};
  Counters any;
  ASSERT_EQ(trace_packet(g, {r, r, r, r}, 0x1u, hits, any, &lim), 0u);
  EXPECT_EQ(any.leaf_visits, 1u);
  EXPECT_EQ(any.culled_pops, 1u);
  EXPECT_EQ(hits[0].t.to_double(), 5.0);
}

// Rules version 4: set-up ends a shadow ray's interval at the light. The same two leaves, the
// light at t = 3.5: the ray is in the left leaf up to t = 4, so its interval [0, 3.5] never
// reaches the right one (no push, no pop); the left square at t = 5 lies beyond the light, so the
// light gets through. (Version 3 pushed the right leaf and culled it at the pop.)
TEST(GoldenLight, ShadowRayIntervalEndsAtTheLight) {
  const Geometry<T> g = two_leaves();
  const Ray<T> r = kTwoLeavesRay;
  const RaySetup<T> su = setup_ray(r, g.bounds, f(3.5));
  EXPECT_EQ(su.tmax.to_double(), 3.5);
  EXPECT_TRUE(su.active);
  SecondaryLimits<T> lim;
  lim.t_lo = f(1e-3);
  lim.t_hi = {f(3.5), T::inf(), T::inf(), T::inf()};
  std::array<Hit<T>, kPacketRays> hits;
  Counters any;
  ASSERT_EQ(trace_packet(g, {r, r, r, r}, 0x1u, hits, any, &lim), 0u);
  EXPECT_EQ(any.leaf_visits, 1u);
  EXPECT_EQ(any.stack_pushes, 0u);
  EXPECT_EQ(any.stack_pops, 0u);
  EXPECT_EQ(hits[0].tri, -1);
  // A limit below the interval's start leaves the ray inactive.
  EXPECT_FALSE(setup_ray(r, g.bounds, f(-1.0)).active);
}

TEST(GoldenLight, FixedPointSumsAndBytes) {
  EXPECT_EQ(light_fixed(T::zero()), 0u);
  EXPECT_EQ(light_fixed(T::one()), kLightOne);
  EXPECT_EQ(light_fixed(f(7.0)), kLightOne) << "a term is clamped to 1";
  EXPECT_EQ(light_fixed(f(-0.5)), 0u);
  EXPECT_EQ(light_fixed(T::nan()), 0u);
  EXPECT_EQ(light_fixed(f(0.5)), kLightOne / 2);
  // 2^-17 is half a unit: the tie goes to the even 0; 3 * 2^-17 goes to 2.
  EXPECT_EQ(light_fixed(f(std::ldexp(1.0, -17))), 0u);
  EXPECT_EQ(light_fixed(f(3 * std::ldexp(1.0, -17))), 2u);
  EXPECT_EQ(light_byte(0), 0);
  EXPECT_EQ(light_byte(kLightOne), 255);
  EXPECT_EQ(light_byte(3 * kLightOne), 255) << "the sum is clamped to 1";
  EXPECT_EQ(light_byte(kLightOne / 2), 128) << "127.5: the tie goes to the even 128";
  EXPECT_EQ(light_byte(257), 1);  // 257 * 255 / 65536 = 0.99998
  EXPECT_EQ(light_byte(128), 0);  // 0.498
}

TEST(GoldenLight, ExponentAndPower) {
  EXPECT_EQ(light_exponent(f(0.0)), 0u);
  EXPECT_EQ(light_exponent(f(-3.0)), 0u);
  EXPECT_EQ(light_exponent(T::nan()), 0u);
  EXPECT_EQ(light_exponent(f(0.5)), 0u);
  EXPECT_EQ(light_exponent(f(1.5)), 2u);
  EXPECT_EQ(light_exponent(f(2.5)), 2u);
  EXPECT_EQ(light_exponent(f(96.078431)), 96u);
  EXPECT_EQ(light_exponent(f(5000.0)), kLightExponentMax);
  EXPECT_EQ(pow_int(f(0.5), 0).to_double(), 1.0);
  EXPECT_EQ(pow_int(f(0.5), 3).to_double(), 0.125);
  EXPECT_EQ(pow_int(f(0.5), 10).to_double(), std::ldexp(1.0, -10));
  // Square and multiply, low bit first, each step rounded: x^5 = x * x^4 with x^4 = (x^2)^2.
  const T x = f(0.9);
  EXPECT_EQ(pow_int(x, 5).bits(), (x * ((x * x) * (x * x))).bits());
}

RenderInput load(const std::string& input) {
  return load_render_input(input, scene::LoadOptions{}, scene::NumberFormat::fp24());
}

// A scene without lights renders as it does with the headlight, whatever --lighting says.
TEST(GoldenLight, SceneWithoutLightsKeepsTheHeadlight) {
  const RenderInput in = load(kRoot + "/scenes/default.json");
  Geometry<T> g = load_geometry<T>(in.image);
  ASSERT_FALSE(g.lights.empty());
  g.lights.clear();
  RenderOptions opt = input_options(in);
  opt.width = 64;
  opt.height = 48;
  opt.progress = false;
  const Frame head = render_golden(g, opt);
  opt.lighting = Lighting::kScene;
  const Frame lit = render_golden(g, opt);
  EXPECT_EQ(lit.rgb, head.rgb);
  EXPECT_TRUE(lit.light_mask.empty());
  EXPECT_EQ(lit.shadow_counters.rays, 0u);
}

// The default scene with its light: deterministic at any thread count; shadows appear (some hit
// pixels facing the light are occluded); the shadow test agrees with Embree's.
TEST(GoldenLight, DefaultSceneLitFrames) {
  const RenderInput in = load(kRoot + "/scenes/default.json");
  const Geometry<T> g = load_geometry<T>(in.image);
  ASSERT_EQ(g.lights.size(), 1u);
  RenderOptions opt = input_options(in);
  opt.width = 128;
  opt.height = 96;
  opt.progress = false;
  opt.lighting = Lighting::kScene;
  opt.threads = 1;
  const Frame f1 = render_golden(g, opt);
  opt.threads = 8;
  const Frame f8 = render_golden(g, opt);
  EXPECT_EQ(f8.rgb, f1.rgb);
  EXPECT_EQ(f8.light_mask, f1.light_mask);
  EXPECT_EQ(f8.shadow_counters.traversal_steps, f1.shadow_counters.traversal_steps);
  EXPECT_EQ(f8.shadow_counters.triangle_tests, f1.shadow_counters.triangle_tests);
  EXPECT_EQ(f1.shadow_counters.errors, 0u);
  uint64_t hits = 0, lit = 0;
  for (size_t p = 0; p < f1.hit_tri.size(); ++p)
    if (f1.hit_tri[p] >= 0) ++hits, lit += f1.light_mask[p] & 1u;
  EXPECT_GT(lit, hits / 4) << "most of the box sees its light";
  EXPECT_LT(lit, hits) << "the boxes cast shadows";
  EXPECT_GT(f1.shadow_counters.rays, 0u);
  EXPECT_LE(f1.shadow_counters.rays, hits);

  const Frame e = render_embree<T>(triangle_soup(*in.scene), opt, soup_lights(*in.scene));
  const LightAgreement la = compare_lights(f1, e, g.lights.size());
  const Agreement ag = compare_frames(f1, e);
  std::printf(
      "[light agreement] default at 128x96: shadow test %.4f%% of %llu (pixel, light) pairs "
      "(%llu lit only by golden, %llu only by embree), PSNR %.2f dB\n",
      100.0 * la.share(), static_cast<unsigned long long>(la.tests),
      static_cast<unsigned long long>(la.only_a_lit),
      static_cast<unsigned long long>(la.only_b_lit), ag.psnr_db);
  EXPECT_GT(la.tests, hits / 2);
  EXPECT_GE(la.share(), 0.99);
}

}  // namespace
}  // namespace rc::test
