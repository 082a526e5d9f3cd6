// The core harness (tb/harness/core_sim_impl.hpp) on its own, around a stand-in with rc_core's
// ports (rc_fake_core.sv) whose framebuffer writes are made from the bits of the records it read:
// checks the wiring of all five memory ports (including the materials' kd field), the packet
// stream (pixel ids), the framebuffer collection, the perf counter read-out, seeded stalls, the
// watchdog and the FST window.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <iterator>
#include <string>

#include "Vrc_fake_core.h"
#include "Vrc_fake_core_hang.h"
#include "core_sim_impl.hpp"
#include "cornell_input.hpp"
#include "job.hpp"

namespace rc::test {
namespace {

using harness::CoreSim;
using harness::CoreSimError;
using harness::CoreSimOptions;
using harness::CoreSimResult;

// What the fake core writes for pixel p (see rc_fake_core.sv).
HitRecord expected_hit(const scene::SceneImage& img, uint32_t p, std::array<uint8_t, 3>& rgb) {
  // The node port's pair (record i, record i + 1 or zero) and the root record (root_node_i).
  const size_t i = p % img.node_count();
  const uint64_t node = img.node(i).raw, next = i + 1 < img.node_count() ? img.node(i + 1).raw : 0;
  const uint64_t root = harness::root_node_record(img);
  const uint32_t l = img.list_entry(p % img.list_size());
  const scene::ShadingRecord sh = img.shading(l);
  const scene::MaterialRecord mat = img.material(sh.material & 0xffffu);
  for (int c = 0; c < 3; ++c) rgb[c] = static_cast<uint8_t>(mat.kd[c]);
  HitRecord h;
  h.tri = static_cast<int32_t>(l);
  h.t = img.triangle_bits(l, 11);
  h.u = sh.normal_bits[0];
  h.v = static_cast<uint32_t>((node ^ next ^ root) >> 40);
  return h;
}

void check_frame(const CoreSimResult& r, const scene::SceneImage& img, uint32_t w, uint32_t h) {
  ASSERT_EQ(r.frame.width, w);
  ASSERT_EQ(r.frame.height, h);
  uint64_t mismatches = 0;
  for (uint32_t p = 0; p < w * h; ++p) {
    std::array<uint8_t, 3> rgb;
    const HitRecord want = expected_hit(img, p, rgb);
    const bool ok = r.frame.hits[p] == want && r.frame.rgb[3 * p] == rgb[0] &&
                    r.frame.rgb[3 * p + 1] == rgb[1] && r.frame.rgb[3 * p + 2] == rgb[2];
    if (!ok && mismatches++ < 5)
      ADD_FAILURE() << "pixel " << p << ": tri " << r.frame.hits[p].tri << " want " << want.tri
                    << ", t " << r.frame.hits[p].t << " want " << want.t << ", u "
                    << r.frame.hits[p].u << " want " << want.u << ", v " << r.frame.hits[p].v
                    << " want " << want.v;
  }
  std::printf("[cases] core harness (fake core) %ux%u: %u cases, %llu mismatches\n", w, h, w * h,
              static_cast<unsigned long long>(mismatches));
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(r.frame.counters.packets, static_cast<uint64_t>((w + 1) / 2) * ((h + 1) / 2));
  EXPECT_EQ(r.frame.counters.rays, static_cast<uint64_t>(w) * h);
  EXPECT_EQ(r.perf[spec::kCorePerfFbWrites], static_cast<uint64_t>(w) * h);
  EXPECT_EQ(r.error_bits, 0u);
  EXPECT_TRUE(r.idle);
  for (const auto& m : r.memory) {
    EXPECT_EQ(m.requests, static_cast<uint64_t>(w) * h);
    EXPECT_EQ(m.responses, m.requests);
  }
  EXPECT_EQ(r.memory[harness::kPortNodes].bytes, 16u * w * h);  // pairs of node records
  EXPECT_EQ(r.memory[harness::kPortMaterials].bytes, 12u * w * h);
  EXPECT_EQ(r.memory[harness::kPortTriangles].bytes, 36u * w * h);
}

TEST(CoreHarness, FakeCoreNoStalls) {
  RenderOptions ro = input_options(cornell());
  ro.width = 15;  // odd: absent rays at the border
  ro.height = 11;
  CoreSimOptions o;
  const CoreSimResult r = CoreSim<Vrc_fake_core>(cornell().image, o).render(ro);
  check_frame(r, cornell().image, ro.width, ro.height);
}

TEST(CoreHarness, FakeCoreWithStalls) {
  RenderOptions ro = input_options(cornell());
  ro.width = 16;
  ro.height = 12;
  for (uint64_t seed : {1u, 2u}) {
    CoreSimOptions o;
    o.stall_seed = seed;
    o.memory[harness::kPortNodes].latency = 3;
    const CoreSimResult r = CoreSim<Vrc_fake_core>(cornell().image, o).render(ro);
    check_frame(r, cornell().image, ro.width, ro.height);
    EXPECT_GT(r.memory[harness::kPortLists].refused_cycles, 0u) << "stalls happened";
  }
}

TEST(CoreHarness, WatchdogNamesThePorts) {
  RenderOptions ro = input_options(cornell());
  ro.width = 4;
  ro.height = 4;
  CoreSimOptions o;
  o.watchdog_cycles = 500;
  try {
    CoreSim<Vrc_fake_core_hang>(cornell().image, o).render(ro);
    FAIL() << "no error";
  } catch (const CoreSimError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("hangs"), std::string::npos) << msg;
    EXPECT_NE(msg.find("nodes port: 1 outstanding"), std::string::npos) << msg;
    EXPECT_NE(msg.find("packets fed 1 of 4"), std::string::npos) << msg;
  }
}

TEST(CoreHarness, TraceWindow) {
  RenderOptions ro = input_options(cornell());
  ro.width = 4;
  ro.height = 4;
  CoreSimOptions o;
  o.trace_path = testing::TempDir() + "/fake_core.fst";
  o.trace_first = 20;
  o.trace_last = 60;
  std::filesystem::remove(o.trace_path);
  {
    const CoreSimResult r = CoreSim<Vrc_fake_core>(cornell().image, o).render(ro);
    EXPECT_GT(r.cycles, 60u);
  }
  ASSERT_TRUE(std::filesystem::exists(o.trace_path));
  EXPECT_GT(std::filesystem::file_size(o.trace_path), 100u);
}

// The trace file must open: an unwritable path ends the run with a message naming it.
TEST(CoreHarness, TraceThatCannotOpen) {
  RenderOptions ro = input_options(cornell());
  ro.width = 4;
  ro.height = 4;
  CoreSimOptions o;
  o.trace_path = "/no/such/dir/t.fst";
  try {
    CoreSim<Vrc_fake_core>(cornell().image, o).render(ro);
    ADD_FAILURE() << "no error for an unwritable trace";
  } catch (const CoreSimError& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/dir/t.fst: cannot open"), std::string::npos)
        << e.what();
  }
}

// run_problems(): what `raycore render --check` and the regression judge besides the frame.
TEST(CoreHarness, RunProblems) {
  RenderOptions ro = input_options(cornell());
  ro.width = 6;
  ro.height = 4;
  const CoreSimResult clean = CoreSim<Vrc_fake_core>(cornell().image, {}).render(ro);
  EXPECT_TRUE(harness::run_problems(clean).empty());
  struct Bad {
    const char* name;
    std::function<void(CoreSimResult&)> apply;
    const char* expect;
  };
  const Bad cases[] = {
      {"watchdog bit", [](CoreSimResult& r) { r.error_bits |= 1u << spec::kCoreStatusWatchdog; },
       "outside the golden model's"},
      {"unknown bit", [](CoreSimResult& r) { r.error_bits |= 0x80u; }, "outside the golden"},
      {"not idle", [](CoreSimResult& r) { r.idle = false; }, "not idle"},
      {"miss with a payload", [](CoreSimResult& r) { r.misses_with_payload = 2; },
       "2 misses carry"},
      {"a write short (core's count)", [](CoreSimResult& r) { --r.perf[spec::kCorePerfFbWrites]; },
       "the core counted 23"},
      {"a write extra (harness)", [](CoreSimResult& r) { ++r.fb_writes; }, "the harness saw 25"},
      {"a kind's rays not counted", [](CoreSimResult& r) { r.rays_fed[1] = 4; },
       "shadow rays: the core counted 0, 4 were fed"},
  };
  size_t mismatches = 0;
  for (const Bad& c : cases) {
    CoreSimResult r = clean;
    c.apply(r);
    const auto problems = harness::run_problems(r);
    const bool ok = problems.size() == 1 && problems[0].find(c.expect) != std::string::npos;
    mismatches += !ok;
    EXPECT_TRUE(ok) << c.name << ": " << (problems.empty() ? "no problem" : problems[0]);
  }
  std::printf("[cases] core harness run_problems: %zu cases, %zu mismatches\n", std::size(cases),
              mismatches);
}

// frame_counter_differences(): which counters `raycore render --check` and the regression
// compare, for a frame without lighting, lit with host passes and lit on chip. Each case changes
// one counter of a run that matches and must give exactly the named difference.
TEST(CoreHarness, FrameCounterDifferences) {
  const auto counters = [](uint64_t base) {
    Counters c;
    c.packets = base;
    c.rays = 4 * base;
    c.nodes_fetched = 5 * base;
    c.inner_visits = 5 * base;
    c.traversal_steps = 17 * base;
    c.leaf_visits = 3 * base;
    c.list_entries = 7 * base;
    c.triangle_tests = 25 * base;
    c.stack_pushes = 2 * base;
    c.stack_pops = 2 * base;
    c.max_stack = base % 5;
    return c;
  };
  Frame gold;
  gold.counters = counters(10);
  gold.shadow_counters = counters(7);
  gold.bounce_counters = counters(3);
  gold.refract_counters = counters(2);
  gold.light_mask.assign(4, 1);
  // Lit with host passes: each kind's own counters.
  CoreSimResult host;
  host.frame = gold;
  host.lit = true;
  // Lit on chip: the totals, and the per-kind counters in the core's perf counters.
  CoreSimResult chip;
  chip.lit = true;
  chip.on_chip_kinds = 0xe;
  chip.frame.light_mask = gold.light_mask;
  chip.frame.counters = gold.counters;
  for (const Counters* k : {&gold.shadow_counters, &gold.bounce_counters, &gold.refract_counters})
    chip.frame.counters.add(*k);
  const Counters* kinds[] = {&gold.counters, &gold.shadow_counters, &gold.bounce_counters,
                             &gold.refract_counters};
  for (size_t k = 0; k < 4; ++k) {
    const size_t at = static_cast<size_t>(spec::kCorePerfPrimaryRays) + 3 * k;
    chip.perf[at] = kinds[k]->rays;
    chip.perf[at + 1] = kinds[k]->traversal_steps;
    chip.perf[at + 2] = kinds[k]->triangle_tests;
  }
  Frame plain_gold;
  plain_gold.counters = gold.counters;
  CoreSimResult plain;
  plain.frame.counters = gold.counters;
  EXPECT_TRUE(harness::frame_counter_differences(plain_gold, plain).empty());
  EXPECT_TRUE(harness::frame_counter_differences(gold, host).empty());
  EXPECT_TRUE(harness::frame_counter_differences(gold, chip).empty());

  struct Case {
    const char* name;
    const Frame* gold;
    const CoreSimResult* run;
    std::function<void(CoreSimResult&)> apply;
    const char* expect;
  };
  const size_t shadow_steps = static_cast<size_t>(spec::kCorePerfPrimaryRays) + 4;
  const Case cases[] = {
      {"plain steps", &plain_gold, &plain,
       [](CoreSimResult& r) { ++r.frame.counters.traversal_steps; }, "traversal_steps"},
      {"host primary pops", &gold, &host, [](CoreSimResult& r) { ++r.frame.counters.stack_pops; },
       "stack_pops"},
      {"host shadow rays", &gold, &host, [](CoreSimResult& r) { ++r.frame.shadow_counters.rays; },
       "shadow rays"},
      {"host refraction tests", &gold, &host,
       [](CoreSimResult& r) { ++r.frame.refract_counters.triangle_tests; },
       "refract triangle_tests"},
      {"chip total node fetches", &gold, &chip,
       [](CoreSimResult& r) { ++r.frame.counters.nodes_fetched; }, "all kinds nodes_fetched"},
      {"chip shadow steps", &gold, &chip, [&](CoreSimResult& r) { ++r.perf[shadow_steps]; },
       "shadow traversal_steps"},
      {"chip mirror rays", &gold, &chip,
       [](CoreSimResult& r) { ++r.perf[static_cast<size_t>(spec::kCorePerfPrimaryRays) + 6]; },
       "bounce rays"},
  };
  size_t mismatches = 0;
  for (const Case& c : cases) {
    CoreSimResult r = *c.run;
    c.apply(r);
    const auto d = harness::frame_counter_differences(*c.gold, r);
    const bool ok = d.size() == 1 && d[0].name == c.expect && d[0].required;
    mismatches += !ok;
    EXPECT_TRUE(ok) << c.name << ": " << (d.empty() ? "no difference" : d[0].text());
  }
  // After an error the work counters may differ (the failing packets' work still in flight):
  // reported, not required.
  Frame failed = gold;
  failed.shadow_counters.errors = 1;
  CoreSimResult r = chip;
  r.frame.counters.errors = 1;
  ++r.perf[shadow_steps];
  const auto d = harness::frame_counter_differences(failed, r);
  EXPECT_TRUE(d.size() == 1 && d[0].name == "shadow traversal_steps" && !d[0].required)
      << (d.empty() ? "no difference" : d[0].text());
  std::printf("[cases] core harness frame_counter_differences: %zu cases, %zu mismatches\n",
              std::size(cases) + 1, mismatches + (d.size() == 1 && !d[0].required ? 0 : 1));
}

}  // namespace
}  // namespace rc::test
