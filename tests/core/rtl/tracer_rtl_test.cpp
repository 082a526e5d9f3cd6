// The tree controller (rtl/core/rc_tracer.sv) through render_rtl() (the modules rc_tracer and
// rc_tracer_t1): the cases the lit scenes of core_rtl_test (CoreRtlLit, on chip) do not cover:
// four lights (point and directional, coloured), depth 0 and the limit, and a core with one
// thread under seeded random stalls on every port (the two lighting ports included) and on the
// framebuffer port. Against the golden model's lit frame at the same depth, bit for bit: every
// pixel's colour, hit record, the lights that reach it and what its first mirror and refraction
// rays hit; the counters of all packets (the core's totals against the golden model's four kinds
// summed) and per ray kind.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "compare.hpp"
#include "compiler.hpp"
#include "core_sim.hpp"
#include "four_lights.hpp"
#include "geometry.hpp"
#include "job.hpp"
#include "scene_cache.hpp"

namespace rc::test {
namespace {

using harness::CoreSimOptions;
using harness::CoreSimResult;

const std::string kRoot = RC_SOURCE_DIR;

struct TracerCase {
  const char* scene;  // under scenes/
  uint32_t width, height;
  uint32_t bounces;
  uint64_t stall_seed;
  bool four_lights;  // three more lights (point and directional, coloured): MaxLights in all
  bool t1 = false;   // around a core with one thread (Vrc_tracer_t1)
};

void PrintTo(const TracerCase& c, std::ostream* os) {
  *os << c.scene << " bounces " << c.bounces << " stall " << c.stall_seed
      << (c.t1 ? " threads 1" : "");
}

// The case's scene, with its extra lights when asked for.
RenderInput case_input(const TracerCase& c) {
  const std::string path = kRoot + "/" + c.scene;
  return c.four_lights ? with_four_lights(load_render_input(path, scene::LoadOptions{},
                                                            scene::NumberFormat::fp24()))
                       : cached_render_input(path);
}

uint64_t differ(const std::vector<int32_t>& a, const std::vector<int32_t>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  uint64_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i] ? 1 : 0;
  return n;
}

class TracerRtl : public testing::TestWithParam<TracerCase> {};

TEST_P(TracerRtl, MatchesGoldenBitForBit) {
  const TracerCase c = GetParam();
  const RenderInput in = case_input(c);
  ASSERT_GT(in.image.light_count(), 0u) << c.scene << ": a lit case needs a scene with lights";
  RenderOptions opt = input_options(in);
  opt.width = c.width;
  opt.height = c.height;
  opt.progress = false;
  opt.lighting = Lighting::kScene;
  opt.max_bounces = c.bounces;
  const Frame gold = render_golden(load_geometry<fp24>(in.image), opt);

  CoreSimOptions so;
  so.stall_seed = c.stall_seed;
  const CoreSimResult r = harness::render_rtl(
      in.image, opt, so, c.t1 ? harness::CoreModel::kThreads1 : harness::CoreModel::kDefault);
  const Frame& f = r.frame;
  ASSERT_TRUE(r.lit);
  ASSERT_NE(r.on_chip_kinds, 0u) << "the secondary rays were made on chip";

  const ExactComparison cmp = compare_exact(gold, f);
  uint64_t light_differ = 0, lit_pairs = 0;
  ASSERT_EQ(gold.light_mask.size(), f.light_mask.size());
  for (size_t i = 0; i < f.light_mask.size(); ++i) {
    light_differ += gold.light_mask[i] != f.light_mask[i] ? 1 : 0;
    lit_pairs += static_cast<uint64_t>(__builtin_popcount(gold.light_mask[i]));
  }
  const uint64_t bounce_differ = differ(gold.bounce_tri, f.bounce_tri);
  const uint64_t refract_differ = differ(gold.refract_tri, f.refract_tri);

  // The core's counters count every packet it traced (the primary packets and the ones the
  // controller made): against the golden model's four kinds summed, and per kind its rays,
  // traversal steps and triangle tests.
  std::vector<std::string> counters;
  for (const CounterDifference& d : harness::frame_counter_differences(gold, r))
    counters.push_back(d.text());
  const auto kinds = harness::kind_counters(r.perf);
  const auto kind = [&kinds](int64_t k) -> const harness::KindCounters& {
    return kinds[static_cast<size_t>(k)];
  };

  const auto u = [](uint64_t v) { return static_cast<unsigned long long>(v); };
  const uint64_t rays = f.counters.rays;
  std::printf(
      "[cases] tracer rtl %s%s%s bounces %u stall %llu %ux%u: %llu cases, %llu mismatches (%llu "
      "cycles; rays: %llu primary, %llu shadow, %llu mirror, %llu refraction; %.3f rays/cycle; "
      "%.0f cycles/s)\n",
      c.scene, c.four_lights ? " (4 lights)" : "", c.t1 ? " threads 1" : "", c.bounces,
      u(c.stall_seed), f.width, f.height, u(cmp.pixels),
      u(cmp.differing + light_differ + bounce_differ + refract_differ + counters.size()),
      u(r.cycles), u(kind(spec::kRayKindPrimary).rays), u(kind(spec::kRayKindShadow).rays),
      u(kind(spec::kRayKindBounce).rays), u(kind(spec::kRayKindRefract).rays),
      r.cycles ? static_cast<double>(rays) / static_cast<double>(r.cycles) : 0.0,
      r.cycles_per_second);
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
  EXPECT_EQ(bounce_differ, 0u) << "pixels whose first mirror ray's hit differs";
  EXPECT_EQ(refract_differ, 0u) << "pixels whose first refraction ray's hit differs";
  for (const std::string& d : counters) ADD_FAILURE() << c.scene << ": counter " << d;
  for (const std::string& p : harness::run_problems(r)) ADD_FAILURE() << c.scene << ": " << p;
  // The case must test something: shadow rays (some occluded, except under the terrain's
  // directional light), and the mirror and glass rays of the scenes that have them.
  EXPECT_GT(gold.shadow_counters.rays, 0u);
  EXPECT_GT(lit_pairs, 0u);
  if (std::string(c.scene) != "scenes/terrain.json") {
    EXPECT_LT(lit_pairs, gold.shadow_counters.rays) << "no shadow ray occluded";
  }
  if (c.bounces > 0 && std::string(c.scene) != "scenes/default.json" &&
      std::string(c.scene) != "scenes/terrain.json") {
    EXPECT_GT(gold.bounce_counters.rays, 0u) << "the mirrors send mirror rays";
  }
  if (c.bounces > 0 && std::string(c.scene) == "scenes/spheres.json") {
    EXPECT_GT(gold.refract_counters.rays, 0u) << "the glass sends refraction rays";
  }
}

const uint32_t kDefaultDepth = static_cast<uint32_t>(spec::kLightMaxBounces);
const uint32_t kLimit = static_cast<uint32_t>(spec::kLightBounceLimit);

// The cases CoreRtlLit (core_rtl_test.cpp) does not have: every lit scene runs there on chip at
// the default memory latency, with stalls and with one thread.
const TracerCase kCases[] = {
    {"scenes/default.json", 40, 30, kDefaultDepth, 4, true},  // four lights, with stalls
    {"scenes/spheres.json", 32, 24, 0, 5, false},             // local shading only
    {"scenes/spheres.json", 32, 24, kLimit, 6, false},        // the deepest trees
    // Around a core with one thread, with stalls: every packet of every tree through it, one at
    // a time.
    {"scenes/default.json", 32, 24, kDefaultDepth, 7, false, true},
    {"scenes/spheres.json", 24, 18, kDefaultDepth, 8, false, true},
};

std::string case_name(const testing::TestParamInfo<TracerCase>& info) {
  std::string n = info.param.scene;
  n = n.substr(n.find('/') + 1);
  n = n.substr(0, n.find('.'));
  for (char& ch : n)
    if (ch == '-') ch = '_';
  return n + (info.param.four_lights ? "_4lights_" : "_") + std::to_string(info.param.width) +
         "_depth" + std::to_string(info.param.bounces) + "_stall" +
         std::to_string(info.param.stall_seed) + (info.param.t1 ? "_t1" : "");
}

INSTANTIATE_TEST_SUITE_P(Scenes, TracerRtl, testing::ValuesIn(kCases), case_name);

}  // namespace
}  // namespace rc::test
