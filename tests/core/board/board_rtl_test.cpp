// The board build (rtl/board/rc_board.sv), verilated and run through tb/harness/board_sim.hpp:
// scenes rendered from block RAM with the on-chip ray generation, against the golden model with
// the same ray source (RaySource::kRayGen), bit for bit: every pixel's rgb and exact hit record,
// the counters read through the register port, the framebuffer read back through its port and the
// register file read back. Corrupted images must give the golden model's error bits. The board
// image's node ROM (pairs of records) and root registers.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "board_sim.hpp"
#include "compare.hpp"
#include "geometry.hpp"
#include "job.hpp"

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

struct SceneCase {
  const char* input;
  uint32_t width, height;
};

class BoardRtl : public testing::TestWithParam<SceneCase> {};

TEST_P(BoardRtl, MatchesGoldenBitForBit) {
  const SceneCase c = GetParam();
  const std::string in = c.input;
  const std::string path = in.rfind("builtin:", 0) == 0 ? in : kRoot + "/" + in;
  const RenderInput ri = load_render_input(path, scene::LoadOptions{}, scene::NumberFormat::fp24());
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
