// The board build (rtl/board/rc_board.sv), verilated and run through tb/harness/board_sim.hpp:
// scenes rendered from block RAM with the on-chip ray generation, against the golden model with
// the same ray source (RaySource::kRayGen), bit for bit: every pixel's rgb and exact hit record,
// the counters read through the register port, the framebuffer read back through its port and the
// register file read back. Corrupted images must give the golden model's error bits. The lit
// board (rc_tracer around the core) against the golden model's lit frame: every pixel's colour,
// hit record, lights and first mirror and refraction hits, the counters over every kind and per
// kind. The board image's node ROM (pairs of records) and root registers, and its light
// registers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "board_sim.hpp"
#include "compare.hpp"
#include "four_lights.hpp"
#include "geometry.hpp"
#include "job.hpp"
#include "scene_cache.hpp"

namespace rc::test {
namespace {

const std::string kRoot = RC_SOURCE_DIR;

void expect_board_matches(const std::string& what, const scene::SceneImage& image,
                          const RenderOptions& opt, uint32_t want_error_bits = 0) {
  RenderOptions gopt = opt;
  gopt.ray_source = RaySource::kRayGen;
  gopt.progress = false;
  const Frame gold = render_golden(load_geometry<fp24>(image), gopt);
  const harness::BoardSimResult r = harness::render_board(image, gopt, {});
  const ExactComparison cmp = compare_exact(gold, r.frame);
  std::vector<std::string> counters;
  for (const CounterDifference& d : counter_differences(gold.counters, r.frame.counters))
    if (d.required) counters.push_back(d.text());
  const uint64_t mismatches =
      cmp.differing + counters.size() + r.fb_readback_differ + r.register_readback_differ;
  std::printf(
      "[cases] board rtl %s %ux%u: %llu cases, %llu mismatches (%llu cycles, %.3f rays/cycle, "
      "%.0f cycles/s; read back: %llu fb, %llu registers differ)\n",
      what.c_str(), opt.width, opt.height, static_cast<unsigned long long>(cmp.pixels),
      static_cast<unsigned long long>(mismatches), static_cast<unsigned long long>(r.cycles),
      r.cycles ? static_cast<double>(r.frame.counters.rays) / static_cast<double>(r.cycles) : 0.0,
      r.cycles_per_second, static_cast<unsigned long long>(r.fb_readback_differ),
      static_cast<unsigned long long>(r.register_readback_differ));
  EXPECT_TRUE(cmp.equal()) << what << ": " << cmp.differing << " pixels differ, the first "
                           << cmp.first;
  for (const std::string& d : counters) ADD_FAILURE() << what << ": counter " << d;
  // The board's core has primary packets only: its per-kind counters are the totals' aliases.
  for (const std::string& p : harness::kind_problems(r.perf, {gold.counters.rays, 0, 0, 0}))
    ADD_FAILURE() << what << ": " << p;
  EXPECT_EQ(r.fb_readback_differ, 0u) << what;
  EXPECT_EQ(r.register_readback_differ, 0u) << what;
  EXPECT_EQ(r.error_bits, want_error_bits) << what;
  EXPECT_EQ(gold.counters.error_bits, want_error_bits) << what;
  EXPECT_GT(r.cycles, 0u);
}

// The lit board: the golden model's lit frame (--lighting scene) from the same rays.
void expect_lit_board_matches(const std::string& what, const scene::SceneImage& image,
                              const RenderOptions& opt) {
  RenderOptions gopt = opt;
  gopt.ray_source = RaySource::kRayGen;
  gopt.lighting = Lighting::kScene;
  gopt.progress = false;
  const Frame gold = render_golden(load_geometry<fp24>(image), gopt);
  ASSERT_FALSE(gold.light_mask.empty()) << what << ": a scene with lights";
  const harness::BoardSimResult r = harness::render_board(image, gopt, {});
  ASSERT_TRUE(r.lit) << what << ": rendered by the lit board";
  const ExactComparison cmp = compare_exact(gold, r.frame);
  harness::CoreSimResult as_sim;  // the counters' check of an on-chip lit run
  as_sim.frame = r.frame;
  as_sim.perf = r.perf;
  as_sim.on_chip_kinds = harness::kTracerKinds;
  std::vector<std::string> counters;
  for (const CounterDifference& d : harness::frame_counter_differences(gold, as_sim))
    if (d.required) counters.push_back(d.text());
  const auto differ = [](const auto& x, const auto& y) {
    uint64_t n = x.size() == y.size() ? 0 : 1;
    for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) n += x[i] != y[i] ? 1 : 0;
    return n;
  };
  const uint64_t lights = differ(gold.light_mask, r.frame.light_mask);
  const uint64_t bounce = differ(gold.bounce_tri, r.frame.bounce_tri);
  const uint64_t refract = differ(gold.refract_tri, r.frame.refract_tri);
  const uint64_t mismatches = cmp.differing + counters.size() + lights + bounce + refract +
                              r.fb_readback_differ + r.register_readback_differ;
  Counters all;
  for (const Counters* c :
       {&gold.counters, &gold.shadow_counters, &gold.bounce_counters, &gold.refract_counters})
    all.add(*c);
  std::printf(
      "[cases] lit board rtl %s %ux%u bounces %u: %llu cases, %llu mismatches (%llu cycles; "
      "rays: %llu primary, %llu shadow, %llu mirror, %llu refraction; %.0f cycles/s)\n",
      what.c_str(), opt.width, opt.height, gopt.max_bounces,
      static_cast<unsigned long long>(cmp.pixels), static_cast<unsigned long long>(mismatches),
      static_cast<unsigned long long>(r.cycles),
      static_cast<unsigned long long>(gold.counters.rays),
      static_cast<unsigned long long>(gold.shadow_counters.rays),
      static_cast<unsigned long long>(gold.bounce_counters.rays),
      static_cast<unsigned long long>(gold.refract_counters.rays), r.cycles_per_second);
  EXPECT_TRUE(cmp.equal()) << what << ": " << cmp.differing << " pixels differ, the first "
                           << cmp.first;
  EXPECT_EQ(lights, 0u) << what << ": light masks differ";
  EXPECT_EQ(bounce, 0u) << what << ": first mirror hits differ";
  EXPECT_EQ(refract, 0u) << what << ": first refraction hits differ";
  for (const std::string& d : counters) ADD_FAILURE() << what << ": counter " << d;
  EXPECT_EQ(r.frame.counters.rays, all.rays) << what << ": every kind's rays";
  for (const std::string& p :
       harness::kind_problems(r.perf, {gold.counters.rays, 0, 0, 0}, harness::kTracerKinds))
    ADD_FAILURE() << what << ": " << p;
  EXPECT_EQ(r.fb_readback_differ, 0u) << what;
  EXPECT_EQ(r.register_readback_differ, 0u) << what;
  EXPECT_EQ(r.error_bits, 0u) << what;
  EXPECT_GT(gold.shadow_counters.rays, 0u) << what << ": shadow rays traced";
}

struct SceneCase {
  const char* input;
  uint32_t width, height;
  uint32_t bounces = 0;      // lit cases: the depth
  bool four_lights = false;  // lit cases: three more lights (with_four_lights())
};

class BoardRtl : public testing::TestWithParam<SceneCase> {};

TEST_P(BoardRtl, MatchesGoldenBitForBit) {
  const SceneCase c = GetParam();
  const std::string in = c.input;
  const std::string path = in.rfind("builtin:", 0) == 0 ? in : kRoot + "/" + in;
  const RenderInput ri = cached_render_input(path);
  RenderOptions opt = input_options(ri);
  opt.width = c.width;
  opt.height = c.height;
  expect_board_matches(in, ri.image, opt);
}

INSTANTIATE_TEST_SUITE_P(Scenes, BoardRtl,
                         testing::Values(SceneCase{"scenes/default.json", 64, 48},
                                         SceneCase{"scenes/cornell.json", 63, 47},
                                         SceneCase{"scenes/spheres.json", 48, 36},
                                         SceneCase{"scenes/cornell.json", 128, 96},
                                         SceneCase{"builtin:spheres", 33, 17},
                                         SceneCase{"builtin:cornell", 1, 1}),
                         [](const testing::TestParamInfo<SceneCase>& i) {
                           std::string n = i.param.input;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n + "_" + std::to_string(i.param.width) + "x" +
                                  std::to_string(i.param.height);
                         });

// A list entry naming a triangle beyond the image: the core's bad-address bit, as in the golden
// model; the board's ROMs answer beyond their depth with an error too.
TEST(BoardRtlErrors, TriangleIndexOutOfBounds) {
  const RenderInput in =
      load_render_input("builtin:cornell", scene::LoadOptions{}, scene::NumberFormat::fp24());
  std::vector<uint8_t> bytes = in.image.bytes();
  const scene::SectionInfo lists = in.image.section(spec::kImageSectionIdLists);
  uint32_t leaf = 0;
  for (uint32_t i = 0; i < in.image.node_count(); ++i)
    if (in.image.node(i).is_leaf() && in.image.node(i).count() >= 2) {
      leaf = i;
      break;
    }
  const uint32_t entry = in.image.node(leaf).first() + 1;
  scene::put_le(&bytes, lists.offset + static_cast<size_t>(entry) * lists.stride,
                in.image.triangle_count() + 7, 4);
  scene::put_le(&bytes, spec::kImageHeaderChecksum, 0, 4);
  scene::put_le(&bytes, spec::kImageHeaderChecksum, scene::image_checksum(bytes), 4);
  const scene::SceneImage bad = scene::SceneImage::from_bytes(std::move(bytes), "corrupted");
  RenderOptions opt = input_options(in);
  opt.width = 48;
  opt.height = 36;
  expect_board_matches("corrupt triangle index", bad, opt, kErrBadAddress);
}

class BoardRtlLit : public testing::TestWithParam<SceneCase> {};

TEST_P(BoardRtlLit, MatchesGoldenBitForBit) {
  const SceneCase c = GetParam();
  const std::string path = kRoot + "/" + c.input;
  const RenderInput ri = c.four_lights
                             ? with_four_lights(load_render_input(path, scene::LoadOptions{},
                                                                  scene::NumberFormat::fp24()))
                             : cached_render_input(path);
  RenderOptions opt = input_options(ri);
  opt.width = c.width;
  opt.height = c.height;
  opt.max_bounces = c.bounces;
  expect_lit_board_matches(std::string(c.input) + (c.four_lights ? " with four lights" : ""),
                           ri.image, opt);
}

// The default scene (one light), the box with a mirror block (also with four lights, point and
// directional, coloured: every light register), the spheres (mirror and glass, at depth 3 and at
// the limit), the box with a glass sphere.
INSTANTIATE_TEST_SUITE_P(Scenes, BoardRtlLit,
                         testing::Values(SceneCase{"scenes/default.json", 32, 24, 3},
                                         SceneCase{"scenes/cornell-mirror.json", 31, 23, 3},
                                         SceneCase{"scenes/spheres.json", 24, 18, 3},
                                         SceneCase{"scenes/spheres.json", 16, 12, 8},
                                         SceneCase{"scenes/cornell-mirror.json", 24, 18, 3, true},
                                         SceneCase{"scenes/cornell-glass.json", 16, 12, 3}),
                         [](const testing::TestParamInfo<SceneCase>& i) {
                           std::string n = i.param.input;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n + "_" + std::to_string(i.param.width) + "x" +
                                  std::to_string(i.param.height) + "_depth" +
                                  std::to_string(i.param.bounces) +
                                  (i.param.four_lights ? "_four_lights" : "");
                         });

// The light registers: count, depth, directional bits, t_eps, the background's format values and
// each light's position and colour, as the golden model loads them; a depth above the limit is
// refused before any work; the headlight board for a scene without --lighting scene.
TEST(BoardImage, LightRegisters) {
  const RenderInput ri = cached_render_input(kRoot + "/scenes/conference.json");
  RenderOptions opt = input_options(ri);
  opt.width = 16;
  opt.height = 12;
  EXPECT_FALSE(harness::make_board_image(ri.image, opt, 12288).lit) << "headlight by default";
  opt.lighting = Lighting::kScene;
  opt.max_bounces = 5;
  const harness::BoardImage b = harness::make_board_image(ri.image, opt, 12288);
  ASSERT_TRUE(b.lit);
  ASSERT_EQ(b.regs.size(), static_cast<size_t>(spec::kBoardLitRegs));
  ASSERT_EQ(b.light_roms.size(), 2u);
  const Geometry<fp24> g = load_geometry<fp24>(ri.image);
  ASSERT_EQ(g.lights.size(), 2u) << "the conference room has two lights";
  EXPECT_EQ(b.regs[spec::kBoardRegLightCount], 2u);
  EXPECT_EQ(b.regs[spec::kBoardRegMaxBounces], 5u);
  EXPECT_EQ(b.regs[spec::kBoardRegTEps], g.t_eps.bits());
  for (size_t l = 0; l < 2; ++l) {
    EXPECT_EQ(b.regs[spec::kBoardRegLightDir] >> l & 1u, g.lights[l].directional ? 1u : 0u);
    for (unsigned a = 0; a < 3; ++a) {
      EXPECT_EQ(b.regs[spec::kBoardRegLights + 6 * l + a], g.lights[l].pos[a].bits());
      EXPECT_EQ(b.regs[spec::kBoardRegLights + 6 * l + 3 + a], g.lights[l].color[a].bits());
    }
  }
  const LitParams<fp24> lp = lit_params<fp24>(5, opt.background);
  for (unsigned c = 0; c < 3; ++c)
    EXPECT_EQ(b.regs[spec::kBoardRegLightBg + c], lp.background[c].bits());
  EXPECT_EQ(b.light_roms[0].records.size(), ri.image.section(spec::kImageSectionIdShading).count);
  opt.max_bounces = static_cast<uint32_t>(spec::kLightBounceLimit) + 1;
  EXPECT_THROW(harness::make_board_image(ri.image, opt, 12288), scene::Error);
}

TEST(BoardRtlErrors, FrameLargerThanTheFramebuffer) {
  const RenderInput in =
      load_render_input("builtin:cornell", scene::LoadOptions{}, scene::NumberFormat::fp24());
  RenderOptions opt = input_options(in);
  opt.width = 1024;
  opt.height = 1024;
  EXPECT_THROW(harness::render_board(in.image, opt, {}), scene::Error);
  EXPECT_THROW(harness::make_board_image(in.image, opt, 12288), scene::Error);
}

// The node ROM answers pairs (docs/memory-format.md, "kd nodes"): line i = {record i + 1 (zero
// for the last node), record i}, 128 bits, in nodes.hex as 32 hex digits (record i + 1 first);
// the root registers hold node 0's record, low word first, in regs.hex too.
TEST(BoardImage, NodeRomPairsAndRootRegisters) {
  const RenderInput in =
      load_render_input("builtin:cornell", scene::LoadOptions{}, scene::NumberFormat::fp24());
  RenderOptions opt = input_options(in);
  opt.width = 16;
  opt.height = 12;
  const harness::BoardImage b = harness::make_board_image(in.image, opt, 12288);
  const harness::BoardRom& rom = b.roms[harness::kPortNodes];
  EXPECT_EQ(rom.name, "nodes");
  EXPECT_EQ(rom.width, 128u);
  const size_t n = in.image.node_count();
  ASSERT_EQ(rom.records.size(), n);
  const std::string dir = testing::TempDir() + "/board_image_pairs";
  harness::write_board_image(b, dir, "builtin:cornell");
  std::ifstream hex(dir + "/nodes.hex");
  uint64_t mismatches = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint64_t lo = in.image.node(i).raw, hi = i + 1 < n ? in.image.node(i + 1).raw : 0;
    const std::vector<uint32_t> want = {static_cast<uint32_t>(lo), static_cast<uint32_t>(lo >> 32),
                                        static_cast<uint32_t>(hi), static_cast<uint32_t>(hi >> 32)};
    if (rom.records[i] != want) ++mismatches;
    char line[40];
    std::snprintf(line, sizeof line, "%016llx%016llx", static_cast<unsigned long long>(hi),
                  static_cast<unsigned long long>(lo));
    std::string got;
    if (!std::getline(hex, got) || got != line) ++mismatches;
  }
  std::string extra;
  EXPECT_FALSE(std::getline(hex, extra)) << "nodes.hex has more lines than nodes";
  EXPECT_EQ(rom.records[n - 1][2] | rom.records[n - 1][3], 0u) << "the last node pairs with zero";
  std::printf("[cases] board node ROM lines (pairs) and nodes.hex: %zu cases, %llu mismatches\n", n,
              static_cast<unsigned long long>(mismatches));
  EXPECT_EQ(mismatches, 0u);

  const uint64_t root = in.image.node(0).raw;
  EXPECT_EQ(b.regs[spec::kBoardRegRoot], static_cast<uint32_t>(root));
  EXPECT_EQ(b.regs[spec::kBoardRegRoot + 1], static_cast<uint32_t>(root >> 32));
  std::ifstream regs(dir + "/regs.hex");
  std::vector<uint32_t> words;
  for (std::string line; std::getline(regs, line);)
    words.push_back(static_cast<uint32_t>(std::stoul(line, nullptr, 16)));
  ASSERT_EQ(words.size(), static_cast<size_t>(spec::kBoardRegs));
  EXPECT_EQ(words[spec::kBoardRegRoot], static_cast<uint32_t>(root));
  EXPECT_EQ(words[spec::kBoardRegRoot + 1], static_cast<uint32_t>(root >> 32));
}

}  // namespace
}  // namespace rc::test
