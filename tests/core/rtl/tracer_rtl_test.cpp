// The tree controller (rtl/core/rc_tracer.sv): scene lighting made on chip at max_bounces 0 (local
// shading and one shadow ray per light and hit, no mirror or refraction rays), verilated and run
// through the harness, against the golden model's lit frame at the same depth, bit for bit: every
// pixel's colour, hit record and lights that reach it; the counters of all packets (the core's
// totals against the golden model's primary plus shadow counters) and per ray kind. Scenes with one
// and two point lights and a directional light, at the default memory latency and with seeded
// random stalls on every port (the two lighting ports included) and on the framebuffer port.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "Vrc_tracer.h"
#include "compare.hpp"
#include "compiler.hpp"
#include "core_sim_impl.hpp"
#include "geometry.hpp"
#include "job.hpp"

namespace rc::harness {
template class CoreSim<Vrc_tracer>;
}

namespace rc::test {
namespace {

using harness::CoreSimOptions;
using harness::CoreSimResult;

const std::string kRoot = RC_SOURCE_DIR;

struct TracerCase {
  const char* scene;  // under scenes/
  uint32_t width, height;
  uint64_t stall_seed;
  bool four_lights;  // three more lights (point and directional, coloured): MaxLights in all
};

// The case's scene, with its extra lights when asked for.
RenderInput case_input(const TracerCase& c) {
  RenderInput in =
      load_render_input(kRoot + "/" + c.scene, scene::LoadOptions{}, scene::NumberFormat::fp24());
  if (!c.four_lights) return in;
  scene::Scene s = *in.scene;
  scene::Light a, b, d;
  a.position = {-0.6, 1.2, 0.5};
  a.color = {1.0, 0.6, 0.3};
  a.intensity = 0.7;
  b.type = scene::Light::Type::kDirectional;
  b.position = {0.3, -1.0, -0.4};
  b.color = {0.4, 0.5, 1.0};
  b.intensity = 0.5;
  d.position = {0.7, 0.3, 0.8};
  d.intensity = 0.3;
  s.lights.push_back(a);
  s.lights.push_back(b);
  s.lights.push_back(d);
  const scene::Compiled cc = scene::compile_scene(s, scene::CompileOptions{});
  return RenderInput{s.name, s, scene::SceneImage::from_bytes(cc.image, s.name), std::nullopt};
}

void PrintTo(const TracerCase& c, std::ostream* os) { *os << c.scene << " stall " << c.stall_seed; }

class TracerRtl : public testing::TestWithParam<TracerCase> {};

TEST_P(TracerRtl, MatchesGoldenAtDepthZero) {
  const TracerCase c = GetParam();
  const RenderInput in = case_input(c);
  ASSERT_GT(in.image.light_count(), 0u) << c.scene << ": a lit case needs a scene with lights";
  RenderOptions opt = input_options(in);
  opt.width = c.width;
  opt.height = c.height;
  opt.progress = false;
  opt.lighting = Lighting::kScene;
  opt.max_bounces = 0;
  const Frame gold = render_golden(load_geometry<fp24>(in.image), opt);

  CoreSimOptions so;
  so.stall_seed = c.stall_seed;
  const CoreSimResult r = harness::CoreSim<Vrc_tracer>(in.image, so).render(opt);
  const Frame& f = r.frame;
  ASSERT_TRUE(r.lit);

  const ExactComparison cmp = compare_exact(gold, f);
  uint64_t light_differ = 0, lit_pairs = 0;
  ASSERT_EQ(gold.light_mask.size(), f.light_mask.size());
  for (size_t i = 0; i < f.light_mask.size(); ++i) {
    light_differ += gold.light_mask[i] != f.light_mask[i] ? 1 : 0;
    lit_pairs += static_cast<uint64_t>(__builtin_popcount(gold.light_mask[i]));
  }
  EXPECT_EQ(gold.bounce_tri, f.bounce_tri) << "max_bounces 0: no mirror rays";
  EXPECT_EQ(gold.refract_tri, f.refract_tri) << "max_bounces 0: no refraction rays";

  // The core's counters count every packet it traced: the primary and the shadow packets.
  Counters all = gold.counters;
  all.add(gold.shadow_counters);
  std::vector<std::string> counters;
  for (const CounterDifference& d : counter_differences(all, f.counters))
    counters.push_back(d.text());
  const auto kinds = harness::kind_counters(r.perf);
  const harness::KindCounters& kp = kinds[static_cast<size_t>(spec::kRayKindPrimary)];
  const harness::KindCounters& ks = kinds[static_cast<size_t>(spec::kRayKindShadow)];
  const auto expect_kind = [&](const char* kind, const harness::KindCounters& k,
                               const Counters& g) {
    if (k.rays != g.rays || k.traversal_steps != g.traversal_steps ||
        k.triangle_tests != g.triangle_tests)
      counters.push_back(std::string(kind) + ": rays " + std::to_string(k.rays) + " (golden " +
                         std::to_string(g.rays) + "), steps " + std::to_string(k.traversal_steps) +
                         " (" + std::to_string(g.traversal_steps) + "), tests " +
                         std::to_string(k.triangle_tests) + " (" +
                         std::to_string(g.triangle_tests) + ")");
  };
  expect_kind("primary", kp, gold.counters);
  expect_kind("shadow", ks, gold.shadow_counters);

  std::printf(
      "[cases] tracer rtl %s stall %llu %ux%u: %llu cases, %llu mismatches (%llu cycles, %llu "
      "primary and %llu shadow rays, %.3f rays/cycle, %llu lit pixel-light pairs, %.0f "
      "cycles/s)\n",
      c.scene, static_cast<unsigned long long>(c.stall_seed), f.width, f.height,
      static_cast<unsigned long long>(cmp.pixels),
      static_cast<unsigned long long>(cmp.differing + light_differ + counters.size()),
      static_cast<unsigned long long>(r.cycles), static_cast<unsigned long long>(kp.rays),
      static_cast<unsigned long long>(ks.rays),
      r.cycles ? static_cast<double>(kp.rays + ks.rays) / static_cast<double>(r.cycles) : 0.0,
      static_cast<unsigned long long>(lit_pairs), r.cycles_per_second);
  if (!cmp.equal()) {
    const auto pix = static_cast<size_t>(cmp.first);
    ADD_FAILURE() << c.scene << ": " << cmp.differing << " of " << cmp.pixels << " pixels differ ("
                  << cmp.rgb_differ << " rgb, " << cmp.hits_differ << " hit records); first: pixel "
                  << pix % f.width << ", " << pix / f.width << ": golden rgb "
                  << int(gold.rgb[3 * pix]) << "," << int(gold.rgb[3 * pix + 1]) << ","
                  << int(gold.rgb[3 * pix + 2]) << " tri " << gold.hits[pix].tri << ", rtl rgb "
                  << int(f.rgb[3 * pix]) << "," << int(f.rgb[3 * pix + 1]) << ","
                  << int(f.rgb[3 * pix + 2]) << " tri " << f.hits[pix].tri;
  }
  EXPECT_EQ(light_differ, 0u) << "pixels whose lights differ";
  for (const std::string& d : counters) ADD_FAILURE() << c.scene << ": counter " << d;
  for (const std::string& p : harness::run_problems(r)) ADD_FAILURE() << c.scene << ": " << p;
  // The case must test something: shadow rays, some of them occluded.
  EXPECT_GT(ks.rays, 0u);
  EXPECT_GT(lit_pairs, 0u);
}

const TracerCase kCases[] = {
    {"scenes/default.json", 64, 48, 0, false},         // one point light under the ceiling
    {"scenes/default.json", 48, 36, 1, false},         // with stalls
    {"scenes/default.json", 40, 30, 4, true},          // four lights, with stalls
    {"scenes/cornell-mirror.json", 48, 36, 2, false},  // mirror materials, lit locally only
    {"scenes/terrain.json", 48, 36, 0, false},         // a directional light: t_hi = +inf
    {"scenes/spheres.json", 48, 36, 3, false},
};

std::string case_name(const testing::TestParamInfo<TracerCase>& info) {
  std::string n = info.param.scene;
  n = n.substr(n.find('/') + 1);
  n = n.substr(0, n.find('.'));
  for (char& ch : n)
    if (ch == '-') ch = '_';
  return n + (info.param.four_lights ? "_4lights_" : "_") + std::to_string(info.param.width) +
         "_stall" + std::to_string(info.param.stall_seed);
}

INSTANTIATE_TEST_SUITE_P(Scenes, TracerRtl, testing::ValuesIn(kCases), case_name);

}  // namespace
}  // namespace rc::test
