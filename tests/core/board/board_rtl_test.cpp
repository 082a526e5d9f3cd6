// The board build (rtl/board/rc_board.sv), verilated and run through tb/harness/board_sim.hpp:
// scenes rendered from block RAM with the on-chip ray generation, against the golden model with
// the same ray source (RaySource::kRayGen), bit for bit: every pixel's rgb and exact hit record,
// the counters read through the register port, the framebuffer read back through its port and the
// register file read back. Corrupted images must give the golden model's error bits.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
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

}  // namespace
}  // namespace rc::test
