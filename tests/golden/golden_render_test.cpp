// Whole frames: determinism across thread counts, agreement with Embree on the shared models, and
// the hits file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "compare.hpp"
#include "embree_engine.hpp"
#include "geometry.hpp"
#include "job.hpp"
#include "models_dir.hpp"

namespace rc::test {
namespace {

const std::string kRoot = RC_SOURCE_DIR;
const std::string kModels = shared_models_dir();

RenderInput load(const std::string& input) {
  return load_render_input(input, scene::LoadOptions{}, scene::NumberFormat::fp24());
}

TEST(GoldenRender, SameImageAndCountsAtOneTwoAndEightThreads) {
  const RenderInput in = load(kRoot + "/scenes/default.json");
  const Geometry<fp24> g = load_geometry<fp24>(in.image);
  RenderOptions opt = input_options(in);
  opt.progress = false;
  opt.threads = 1;
  const Frame f1 = render_golden(g, opt);
  EXPECT_EQ(f1.counters.errors, 0u);
  EXPECT_GT(f1.counters.triangle_tests, 0u);
  for (unsigned threads : {2u, 8u}) {
    opt.threads = threads;
    const Frame fn = render_golden(g, opt);
    EXPECT_EQ(fn.rgb, f1.rgb) << threads << " threads";
    EXPECT_EQ(fn.hit_tri, f1.hit_tri) << threads << " threads";
    EXPECT_EQ(0, std::memcmp(fn.hit_t.data(), f1.hit_t.data(), f1.hit_t.size() * 4));
    EXPECT_EQ(fn.counters.traversal_steps, f1.counters.traversal_steps);
    EXPECT_EQ(fn.counters.triangle_tests, f1.counters.triangle_tests);
    EXPECT_EQ(fn.counters.nodes_fetched, f1.counters.nodes_fetched);
    EXPECT_EQ(fn.counters.stack_pushes, f1.counters.stack_pushes);
    EXPECT_EQ(fn.counters.max_stack, f1.counters.max_stack);
  }
}

TEST(GoldenRender, HitsFileLayout) {
  const RenderInput in = load("builtin:cornell");
  RenderOptions opt = input_options(in);
  opt.width = 33;  // odd sizes: packets at the border have absent rays
  opt.height = 17;
  opt.progress = false;
  const Frame f = render_golden(load_geometry<fp24>(in.image), opt);
  const std::string path = testing::TempDir() + "/hits.bin";
  write_hits(path, f);
  std::ifstream file(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 16u + 8u * 33 * 17);
  EXPECT_EQ(0, std::memcmp(bytes.data(), "RCHITS1\0", 8));
  uint32_t w, h;
  std::memcpy(&w, &bytes[8], 4);
  std::memcpy(&h, &bytes[12], 4);
  EXPECT_EQ(w, 33u);
  EXPECT_EQ(h, 17u);
  size_t hits = 0;
  for (size_t i = 0; i < f.hit_tri.size(); ++i) {
    int32_t tri;
    float t;
    std::memcpy(&tri, &bytes[16 + 8 * i], 4);
    std::memcpy(&t, &bytes[20 + 8 * i], 4);
    EXPECT_EQ(tri, f.hit_tri[i]);
    EXPECT_EQ(t, f.hit_t[i]);
    hits += tri >= 0;
  }
  EXPECT_GT(hits, f.hit_tri.size() / 2) << "the Cornell box fills most of the frame";
}

// Hit agreement with Embree: both miss, or both hit the same triangle.
struct AgreementCase {
  const char* input;  // scenes/... (repository) or a path under ../shared/models
  bool auto_camera;
  bool needs_models;  // the input reads ../shared/models
};

class GoldenVsEmbree : public testing::TestWithParam<AgreementCase> {};

TEST_P(GoldenVsEmbree, HitAgreementAtLeast99Percent) {
  const AgreementCase c = GetParam();
  std::string input = c.input;
  input = (input.rfind("scenes/", 0) == 0 ? kRoot : kModels) + "/" + input;
  if (c.needs_models && kModels.empty())
    GTEST_SKIP() << "the shared test models are not there (../shared/models beside the "
                    "repository, or RAYCORE_MODELS_PATH)";
  const RenderInput in = load(input);
  RenderOptions opt = input_options(in);
  if (c.auto_camera) opt.camera = auto_camera_for(in.image);
  opt.width = 320;
  opt.height = 240;
  opt.progress = false;
  const Frame g = render_golden(load_geometry<fp24>(in.image), opt);
  const Frame e = render_embree<fp24>(triangle_soup(*in.scene), opt);
  const Agreement a = compare_frames(g, e);
  std::printf(
      "[agreement] %s at %ux%u: %.4f%% (%llu of %llu pixels differ: %llu different "
      "triangle (%llu at the same depth), %llu only golden hits, %llu only embree hits), "
      "PSNR %.2f dB, "
      "golden %.0f rays/s, embree %.0f rays/s\n",
      c.input, opt.width, opt.height, 100.0 * a.share(),
      static_cast<unsigned long long>(a.pixels - a.agree),
      static_cast<unsigned long long>(a.pixels), static_cast<unsigned long long>(a.different_tri),
      static_cast<unsigned long long>(a.same_depth), static_cast<unsigned long long>(a.only_a_hits),
      static_cast<unsigned long long>(a.only_b_hits), a.psnr_db,
      static_cast<double>(g.counters.rays) / g.seconds,
      static_cast<double>(e.counters.rays) / e.seconds);
  EXPECT_EQ(g.counters.errors, 0u);
  EXPECT_GE(a.share(), 0.99);
  EXPECT_GT(a.pixels - a.both_miss, a.pixels / 25) << "the view should show the model";
}

INSTANTIATE_TEST_SUITE_P(Models, GoldenVsEmbree,
                         testing::Values(AgreementCase{"bunny/bunny.obj", true, true},
                                         AgreementCase{"suzanne/suzanne_cc2.obj", true, true},
                                         AgreementCase{"teapot/teapot.obj", true, true},
                                         AgreementCase{"dragon/dragon.obj", true, true},
                                         AgreementCase{"cornell/CornellBox-Original.obj", true,
                                                       true},
                                         AgreementCase{"scenes/sponza.json", false, true},
                                         AgreementCase{"scenes/conference.json", false, true},
                                         AgreementCase{"scenes/default.json", false, false},
                                         AgreementCase{"scenes/spheres.json", false, false}),
                         [](const testing::TestParamInfo<AgreementCase>& param_info) {
                           std::string n = param_info.param.input;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace rc::test
