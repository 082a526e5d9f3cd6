// The whole core (rtl/core/rc_core.sv), verilated and run through the harness
// (tb/harness/core_sim.hpp), against the golden model (tb/golden/render.hpp), bit for bit: every
// pixel's rgb and exact hit record (triangle, t, u, v) and the counters, for every scene of
// scenes/, the builtin scenes and the shared models, at the default memory latency without stalls,
// with seeded random stalls (two seeds), and at Threads = 1. Scenes lit by their own lights
// (shadow packets traced by the core) must give the golden model's colours, lights per pixel and
// shadow counters too. Corrupted images (the error paths) must give the golden model's error
// bits, counters and (all-miss) pixels, and must not hang.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "compare.hpp"
#include "core_sim.hpp"
#include "geometry.hpp"
#include "job.hpp"
#include "models_dir.hpp"
#include "scene_cache.hpp"

namespace rc::test {
namespace {

using harness::CoreModel;
using harness::CoreSimOptions;
using harness::CoreSimResult;

const std::string kRoot = RC_SOURCE_DIR;
const std::string kModels = shared_models_dir();

std::string hit_text(const HitRecord& h) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "tri %d t %.9g (0x%06x) u %.9g (0x%06x) v %.9g (0x%06x)", h.tri,
                fp24::from_bits(h.t).to_double(), h.t, fp24::from_bits(h.u).to_double(), h.u,
                fp24::from_bits(h.v).to_double(), h.v);
  return buf;
}

// Compares the RTL's frame with the golden model's; prints a [cases] line and, on a mismatch,
// the first differing pixel with its packet and both hit records. Counters: all of them must
// match for an image without errors; after an error only packets, rays, failed packets and the
// error bits must (CounterDifference::required; the others are printed).
// `repro`: the raycore command that reruns the case (empty where there is none);
// `model`: the core model that ran (for the efficiency's ideal).
void expect_bit_exact(const std::string& what, const Frame& gold, const CoreSimResult& r,
                      const std::string& repro = "", CoreModel model = CoreModel::kDefault) {
  const Frame& f = r.frame;
  const ExactComparison cmp = compare_exact(gold, f);
  std::vector<std::string> counters;
  for (const CounterDifference& d : harness::frame_counter_differences(gold, r)) {
    if (d.required)
      counters.push_back(d.text());
    else
      std::printf("%s: counter after an error (allowed to differ) %s\n", what.c_str(),
                  d.text().c_str());
  }
  // Scene lighting: the lights that reach each pixel, what its first mirror and refraction rays
  // hit, and the secondary rays' counters.
  uint64_t light_differ = 0;
  EXPECT_EQ(gold.light_mask.size(), f.light_mask.size()) << what << ": lit in one engine only";
  for (size_t i = 0; i < std::min(gold.light_mask.size(), f.light_mask.size()); ++i)
    light_differ += gold.light_mask[i] != f.light_mask[i] ? 1 : 0;
  EXPECT_EQ(gold.bounce_tri.size(), f.bounce_tri.size()) << what << ": lit in one engine only";
  for (size_t i = 0; i < std::min(gold.bounce_tri.size(), f.bounce_tri.size()); ++i)
    light_differ += gold.bounce_tri[i] != f.bounce_tri[i] ? 1 : 0;
  EXPECT_EQ(gold.refract_tri.size(), f.refract_tri.size()) << what << ": lit in one engine only";
  for (size_t i = 0; i < std::min(gold.refract_tri.size(), f.refract_tri.size()); ++i)
    light_differ += gold.refract_tri[i] != f.refract_tri[i] ? 1 : 0;
  std::printf(
      "[cases] core rtl %s %ux%u: %llu cases, %llu mismatches (%llu cycles, %.3f rays/cycle, "
      "efficiency %.3f, %.0f cycles/s)\n",
      what.c_str(), f.width, f.height, static_cast<unsigned long long>(cmp.pixels),
      static_cast<unsigned long long>(cmp.differing + light_differ + counters.size()),
      static_cast<unsigned long long>(r.cycles),
      r.cycles ? static_cast<double>(f.counters.rays) / static_cast<double>(r.cycles) : 0.0,
      r.cycles
          ? static_cast<double>(harness::ideal_cycles(f.counters, harness::isect_interval(model))) /
                static_cast<double>(r.cycles)
          : 0.0,
      r.cycles_per_second);
  if (!cmp.equal()) {
    const auto pix = static_cast<size_t>(cmp.first);
    const uint32_t x = static_cast<uint32_t>(pix % f.width),
                   y = static_cast<uint32_t>(pix / f.width);
    ADD_FAILURE() << what << ": " << cmp.differing << " of " << cmp.pixels << " pixels differ ("
                  << cmp.rgb_differ << " rgb, " << cmp.hits_differ
                  << " hit records); first: pixel (" << x << ", " << y << "), packet (" << x / 2
                  << ", " << y / 2 << ") ray " << ((x & 1u) | (y & 1u) << 1)
                  << "\n  golden: " << hit_text(gold.hits[pix]) << " rgb " << int(gold.rgb[3 * pix])
                  << "," << int(gold.rgb[3 * pix + 1]) << "," << int(gold.rgb[3 * pix + 2])
                  << "\n  rtl:    " << hit_text(f.hits[pix]) << " rgb " << int(f.rgb[3 * pix])
                  << "," << int(f.rgb[3 * pix + 1]) << "," << int(f.rgb[3 * pix + 2])
                  << (repro.empty() ? "" : "\n  rerun: " + repro);
  }
  if (light_differ)
    ADD_FAILURE() << what << ": " << light_differ
                  << " pixel entries differ in the lights that reach them or the triangle their "
                     "first mirror ray hits"
                  << (repro.empty() ? "" : "\n  rerun: " + repro);
  for (const std::string& d : counters)
    ADD_FAILURE() << what << ": counter " << d << (repro.empty() ? "" : "\n  rerun: " + repro);
  // The checks `raycore render --check` makes too: idle at the end, no miss with a hit record,
  // one framebuffer write per pixel, no watchdog or unknown error bit.
  for (const std::string& p : harness::run_problems(r)) ADD_FAILURE() << what << ": " << p;
}

//////////////////////////////////////////
// Scenes and models, in several modes  //
//////////////////////////////////////////

struct SceneCase {
  const char* input;  // scenes/... or builtin:... (repository) or a path under ../shared/models
  bool auto_camera;
  bool needs_models;
  uint32_t width, height;
};

struct Mode {
  const char* name;
  CoreModel model;
  uint64_t stall_seed;
};

const Mode kModes[] = {
    {"lat16", CoreModel::kDefault, 0},      {"stall1", CoreModel::kDefault, 1},
    {"stall2", CoreModel::kDefault, 2},     {"t1", CoreModel::kThreads1, 0},
    {"t1_stall3", CoreModel::kThreads1, 3}, {"i1_stall4", CoreModel::kIsect1, 4},
};

void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.input; }

std::string input_path(const SceneCase& c) {
  const std::string in = c.input;
  if (in.rfind("builtin:", 0) == 0) return in;
  return (in.rfind("scenes/", 0) == 0 ? kRoot : kModels) + "/" + in;
}

// The input as the command line names it from the repository root.
std::string cli_input(const SceneCase& c) {
  const std::string in = c.input;
  if (in.rfind("builtin:", 0) == 0 || in.rfind("scenes/", 0) == 0) return in;
  return "../shared/models/" + in;
}

// A case's render options: its camera (or the automatic one), its size, no progress.
RenderOptions case_options(const SceneCase& c, const RenderInput& in) {
  RenderOptions opt = input_options(in);
  if (c.auto_camera) opt.camera = auto_camera_for(in.image);
  opt.width = c.width;
  opt.height = c.height;
  opt.progress = false;
  return opt;
}

RenderInput case_input(const SceneCase& c) { return cached_render_input(input_path(c)); }

// Skips the test when the case needs the shared models and they are not there (make test then
// fails: a skipped check is not a pass).
#define RC_SKIP_WITHOUT_MODELS(c)                                                      \
  if ((c).needs_models && kModels.empty())                                             \
  GTEST_SKIP() << "the shared test models are not there (../shared/models beside the " \
                  "repository, or RAYCORE_MODELS_PATH)"

// The one-thread core runs its cases at half the width and height (rounded up, so odd sizes
// stay odd where they were): it has one packet in flight, so a frame takes about as many cycles
// as the default core's at four times the pixels.
SceneCase half_size(SceneCase c) {
  c.width = (c.width + 1) / 2;
  c.height = (c.height + 1) / 2;
  return c;
}

// The shared scene cache (tests/scene_cache.hpp) gives what load_render_input() gives: the same
// image bytes and the same camera to the last bit, when it compiles the input (cold) and when it
// reads the files another process wrote (warm); a scene without a camera stays without one. The
// scene file's camera has values no short decimal holds (0.1, 1/3, 39.3 + 1e-9).
TEST(SceneCache, SameImageAndCameraAsACompile) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() /
                       ("rc_scene_cache_test_" + std::to_string(static_cast<long>(::getpid())));
  fs::remove_all(dir);
  fs::create_directories(dir / "src");
  const std::string scene_file = (dir / "src" / "box.json").string();
  {
    std::ofstream f(scene_file);
    f << R"({"meshes": [{"builtin": "cornell"}], "camera": {"eye": [0.1, 1.0000000001, )"
      << R"(3.3333333333333335], "look": [0, 0.9999999999, 0], "up": [0, 1, 0], )"
      << R"("fov": 39.300000001}, "lights": [{"position": [0, 1.9, 0]}]})";
  }
  const char* old = std::getenv("RC_TEST_SCENE_CACHE");
  const std::string saved = old ? old : "";
  ASSERT_EQ(::setenv("RC_TEST_SCENE_CACHE", (dir / "cache").c_str(), 1), 0);
  for (const std::string& input : {scene_file, std::string("builtin:spheres")}) {
    const RenderInput ref =
        load_render_input(input, scene::LoadOptions{}, scene::NumberFormat::fp24());
    for (const char* pass : {"cold", "warm"}) {
      const RenderInput in = cached_render_input(input);
      EXPECT_EQ(in.name, ref.name) << input << " " << pass;
      EXPECT_TRUE(in.image.bytes() == ref.image.bytes()) << input << " " << pass;
      ASSERT_EQ(in.camera.has_value(), ref.camera.has_value()) << input << " " << pass;
      if (ref.camera) {
        const auto a = camera_values(*in.camera);
        const auto b = camera_values(*ref.camera);
        EXPECT_EQ(std::memcmp(a.data(), b.data(), sizeof a), 0)
            << input << " " << pass << ": camera";
      }
    }
  }
  EXPECT_TRUE(fs::exists(dir / "cache" / "builtin_spheres.rcimg")) << "the cache was written";
  if (old)
    ::setenv("RC_TEST_SCENE_CACHE", saved.c_str(), 1);
  else
    ::unsetenv("RC_TEST_SCENE_CACHE");
  fs::remove_all(dir);
}

class CoreRtl : public testing::TestWithParam<std::tuple<SceneCase, int>> {};

TEST_P(CoreRtl, MatchesGoldenBitForBit) {
  SceneCase c = std::get<0>(GetParam());
  const Mode& mode = kModes[std::get<1>(GetParam())];
  RC_SKIP_WITHOUT_MODELS(c);
  if (mode.model == CoreModel::kThreads1) c = half_size(c);
  const RenderInput in = case_input(c);
  const RenderOptions opt = case_options(c, in);
  const Frame gold = render_golden(load_geometry<fp24>(in.image), opt);
  CoreSimOptions so;
  so.stall_seed = mode.stall_seed;
  const CoreSimResult r = harness::render_rtl(in.image, opt, so, mode.model);
  const std::string repro =
      "./build/tb/app/raycore render " + cli_input(c) +
      " --engine rtl --check -o /tmp/rc_case.png --size " + std::to_string(c.width) + "x" +
      std::to_string(c.height) + (c.auto_camera ? " --auto-camera" : "") +
      (mode.stall_seed ? " --stall-seed " + std::to_string(mode.stall_seed) : "") +
      (mode.model == CoreModel::kThreads1 ? " --threads-rtl 1" : "") +
      (mode.model == CoreModel::kIsect1 ? " --isect-interval-rtl 1" : "");
  expect_bit_exact(std::string(c.input) + " " + mode.name, gold, r, repro, mode.model);
  EXPECT_EQ(gold.counters.errors, 0u);
  if (mode.stall_seed != 0) {
    uint64_t refused = 0;
    for (const auto& m : r.memory) refused += m.refused_cycles;
    EXPECT_GT(refused, 0u) << "the stalls happened";
  }
}

// Sizes: large enough to cover the picture, small enough that the suite stays fast (see
// tests/core/rtl/CMakeLists.txt for the time budget). Odd sizes exercise absent rays.
const SceneCase kScenes[] = {
    {"scenes/default.json", false, false, 96, 72},
    {"scenes/cornell.json", false, false, 65, 49},
    {"scenes/spheres.json", false, false, 96, 72},
    {"scenes/terrain.json", false, false, 80, 60},
    {"scenes/sponza.json", false, true, 64, 48},
    {"scenes/conference.json", false, true, 64, 48},
    {"builtin:spheres", true, false, 80, 60},
    {"bunny/bunny.obj", true, true, 64, 48},
    {"bunny/bunny_lo.obj", true, true, 80, 60},
    {"suzanne/suzanne.obj", true, true, 80, 60},
    {"suzanne/suzanne_cc2.obj", true, true, 64, 48},
    {"teapot/teapot.obj", true, true, 64, 48},
    {"dragon/dragon.obj", true, true, 64, 48},
    {"cornell/CornellBox-Original.obj", true, true, 80, 60},
    {"cornell/CornellBox-Empty-RG.obj", true, true, 80, 60},
    {"cornell/CornellBox-Glossy.obj", true, true, 80, 60},
    {"cornell/CornellBox-Mirror.obj", true, true, 80, 60},
    {"cornell/CornellBox-Sphere.obj", true, true, 80, 60},
    {"spheres/sphere-cylcoords-1k.obj", true, true, 80, 60},
    {"spheres/sphere-cylcoords-4k.obj", true, true, 64, 48},
    {"spheres/sphere-cylcoords-16k.obj", true, true, 64, 48},
};

std::string case_name(const testing::TestParamInfo<std::tuple<SceneCase, int>>& info) {
  std::string n = std::get<0>(info.param).input;
  n += std::string("_") + kModes[std::get<1>(info.param)].name;
  for (char& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Scenes, CoreRtl,
                         testing::Combine(testing::ValuesIn(kScenes), testing::Range(0, 6)),
                         case_name);

//////////////////////////////////////////////////
// Scene lighting: shadow packets in the core   //
//////////////////////////////////////////////////

// The scenes' own lights (docs/architecture.md, "Lighting", "The tracer"): on chip, the tree
// controller around the core (rc_tracer) makes each pixel's shadow, mirror and refraction packets
// from the core's hits and sums its colour; on the host (SecondaryPath::kHost), the core traces
// the primary frame, then each level's secondary packets in passes of their own
// (harness::render_rtl). The colours, the lights per pixel, the first mirror and refraction hits
// and the counters must be the golden model's. The one-thread cases run at half the size
// (half_size()).
class CoreRtlLit : public testing::TestWithParam<std::tuple<SceneCase, int, bool>> {};

// The lit case whose view has no occluder (the terrain under its directional light at 64x48:
// every shadow ray reaches the light); it covers the directional light's limit, +inf.
const char* const kUnshadowed = "scenes/terrain.json";

TEST_P(CoreRtlLit, MatchesGoldenBitForBit) {
  SceneCase c = std::get<0>(GetParam());
  const Mode& mode = kModes[std::get<1>(GetParam())];
  const bool host = std::get<2>(GetParam());
  RC_SKIP_WITHOUT_MODELS(c);
  if (mode.model == CoreModel::kThreads1) c = half_size(c);
  const RenderInput in = case_input(c);
  ASSERT_GT(in.image.light_count(), 0u) << c.input << ": a lit case needs a scene with lights";
  RenderOptions opt = case_options(c, in);
  opt.lighting = Lighting::kScene;
  const Frame gold = render_golden(load_geometry<fp24>(in.image), opt);
  CoreSimOptions so;
  so.stall_seed = mode.stall_seed;
  so.secondary = host ? harness::SecondaryPath::kHost : harness::SecondaryPath::kOnChip;
  const CoreSimResult r = harness::render_rtl(in.image, opt, so, mode.model);
  ASSERT_TRUE(r.lit);
  EXPECT_EQ(r.on_chip_kinds != 0, !host) << "the secondary rays were made where asked";
  const std::string repro =
      "./build/tb/app/raycore render " + cli_input(c) +
      " --engine rtl --lighting scene --check -o /tmp/rc_case.png --size " +
      std::to_string(c.width) + "x" + std::to_string(c.height) +
      (c.auto_camera ? " --auto-camera" : "") +
      (mode.stall_seed ? " --stall-seed " + std::to_string(mode.stall_seed) : "") +
      (mode.model == CoreModel::kThreads1 ? " --threads-rtl 1" : "") +
      (host ? " --secondary host" : "");
  expect_bit_exact(std::string(c.input) + " lit " + (host ? "host " : "chip ") + mode.name, gold, r,
                   repro, mode.model);
  const Counters& sc = gold.shadow_counters;
  if (host)
    std::printf(
        "  shadow passes: %llu packets, %llu rays, %llu cycles (primary %llu); golden: %llu shadow "
        "rays, %llu culled pops; bounce passes: %llu packets, %llu rays, %llu cycles; refract "
        "passes: %llu packets, %llu rays, %llu cycles\n",
        static_cast<unsigned long long>(r.shadow.packets),
        static_cast<unsigned long long>(r.frame.shadow_counters.rays),
        static_cast<unsigned long long>(r.shadow.cycles), static_cast<unsigned long long>(r.cycles),
        static_cast<unsigned long long>(sc.rays), static_cast<unsigned long long>(sc.culled_pops),
        static_cast<unsigned long long>(r.bounce.packets),
        static_cast<unsigned long long>(r.frame.bounce_counters.rays),
        static_cast<unsigned long long>(r.bounce.cycles),
        static_cast<unsigned long long>(r.refract.packets),
        static_cast<unsigned long long>(r.frame.refract_counters.rays),
        static_cast<unsigned long long>(r.refract.cycles));
  EXPECT_GT(sc.rays, 0u) << "shadow rays were traced";
  if (!host) {
    const auto kc = harness::kind_counters(r.perf);
    std::printf(
        "  on chip: %llu cycles; rays: %llu primary, %llu shadow, %llu mirror, %llu "
        "refraction\n",
        static_cast<unsigned long long>(r.cycles), static_cast<unsigned long long>(kc[0].rays),
        static_cast<unsigned long long>(kc[1].rays), static_cast<unsigned long long>(kc[2].rays),
        static_cast<unsigned long long>(kc[3].rays));
  }
  if (std::string(c.input) == "scenes/spheres.json" ||
      std::string(c.input) == "scenes/cornell-mirror.json") {
    EXPECT_GT(gold.bounce_counters.rays, 0u) << "the mirrors send mirror rays";
  }
  if (std::string(c.input) == "scenes/spheres.json" ||
      std::string(c.input) == "scenes/cornell-glass.json") {
    EXPECT_GT(gold.refract_counters.rays, 0u) << "the glass sends refraction rays";
  }
  // Light reaches some hits, and (where the view has occluders) is blocked at others.
  uint64_t lit_pairs = 0;
  for (uint32_t m : gold.light_mask) lit_pairs += static_cast<uint64_t>(__builtin_popcount(m));
  EXPECT_GT(lit_pairs, 0u);
  if (std::string(c.input) != kUnshadowed) {
    EXPECT_LT(lit_pairs, sc.rays) << "no ray occluded";
  }
}

const SceneCase kLitScenes[] = {
    {"scenes/default.json", false, false, 64, 48},
    {"scenes/cornell.json", false, false, 65, 49},
    {"scenes/cornell-mirror.json", false, false, 64, 48},  // a mirror block
    {"scenes/spheres.json", false, false, 64, 48},
    {"scenes/terrain.json", false, false, 64, 48},  // a directional light: t_hi = +inf
    {"scenes/conference.json", false, true, 48, 36},
    {"scenes/cornell-glass.json", false, true, 64, 48},  // a mirror sphere and a glass sphere
};

std::string lit_case_name(const testing::TestParamInfo<std::tuple<SceneCase, int, bool>>& info) {
  std::string n = std::get<0>(info.param).input;
  n += std::string(std::get<2>(info.param) ? "_host_" : "_chip_") +
       kModes[std::get<1>(info.param)].name;
  for (char& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

// On chip: lat16, stall1, t1 (kModes 0, 1, 3); host passes: lat16 (the one-thread core's
// secondary packets are CoreRtlKinds's t1 cases, below).
INSTANTIATE_TEST_SUITE_P(OnChip, CoreRtlLit,
                         testing::Combine(testing::ValuesIn(kLitScenes), testing::Values(0, 1, 3),
                                          testing::Values(false)),
                         lit_case_name);
INSTANTIATE_TEST_SUITE_P(Host, CoreRtlLit,
                         testing::Combine(testing::ValuesIn(kLitScenes), testing::Values(0),
                                          testing::Values(true)),
                         lit_case_name);

// A point light between a floor (y = 0) and a ceiling (y = 2), all in one leaf (a tree of depth
// 0): every shadow ray meets the other quad beyond the light, which must not occlude (only hits
// before the light do: a shadow ray's best starts at {dist, -1}). The camera, between the two,
// sees both, so shadow rays go up and down. Set-up's limit alone cannot keep the far quad out
// here: its leaf is the ray's.
TEST(CoreRtlLitDirected, QuadBeyondTheLightInTheSameLeafDoesNotShadow) {
  scene::Scene s;
  s.name = "light between two quads";
  s.source = "test";
  scene::Mesh m;
  m.source = "test";
  m.vertices = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1},
                {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}};
  m.material = {0, 0, 0, 0};
  m.line = {0, 0, 0, 0};
  m.materials = {scene::Material{}};
  s.meshes = {m};
  scene::Camera cam;
  cam.eye = {0.0, 1.0, 2.5};
  cam.look = {0.0, 1.0, 0.0};
  cam.fov_deg = 90.0;
  s.camera = cam;
  s.width = 40;
  s.height = 30;
  scene::Light light;
  light.position = {0.0, 1.0, 0.0};
  s.lights = {light};
  scene::CompileOptions co;
  co.kd.max_depth = 0;
  const scene::Compiled c = scene::compile_scene(s, co);
  RenderInput in{s.name, s, scene::SceneImage::from_bytes(c.image, s.name), std::nullopt, s.camera};
  ASSERT_EQ(in.image.node_count(), 1u) << "the quads share one leaf";
  RenderOptions opt = input_options(in);
  opt.progress = false;
  opt.lighting = Lighting::kScene;
  const Frame gold = render_golden(load_geometry<fp24>(in.image), opt);
  const CoreSimResult r = harness::render_rtl(in.image, opt, CoreSimOptions{});
  expect_bit_exact("quads beyond the light", gold, r);
  uint64_t lit_pairs = 0, floor = 0, ceiling = 0;
  for (size_t i = 0; i < gold.light_mask.size(); ++i) {
    lit_pairs += static_cast<uint64_t>(__builtin_popcount(gold.light_mask[i]));
    floor += gold.hits[i].tri == 0 || gold.hits[i].tri == 1 ? 1 : 0;
    ceiling += gold.hits[i].tri == 2 || gold.hits[i].tri == 3 ? 1 : 0;
  }
  EXPECT_GT(floor, 0u);
  EXPECT_GT(ceiling, 0u);
  EXPECT_EQ(lit_pairs, floor + ceiling) << "every hit sees the light";
  // On chip (the default): the core's own count of shadow rays.
  ASSERT_NE(r.on_chip_kinds, 0u);
  EXPECT_EQ(harness::kind_counters(r.perf)[static_cast<size_t>(spec::kRayKindShadow)].rays,
            floor + ceiling);
}

//////////////////////////////////////////////
// Every ray kind at once: per-kind counters //
//////////////////////////////////////////////

// Primary, shadow, mirror and refraction packets in one run, shuffled (seed 26), so that packets
// of every kind are in flight together, as the light unit's tree controller will feed them: the
// spheres' primary packets and the children of their hits (lit_work()). Every ray's hit record
// and colour (a primary ray's headlight shade, 0 for a secondary ray), the counters, and the
// core's own counters per kind (rays, traversal steps, triangle tests) must be the golden
// model's.
class CoreRtlKinds : public testing::TestWithParam<int> {};

TEST_P(CoreRtlKinds, MixedKindsMatchGoldenPerKind) {
  const Mode& mode = kModes[GetParam()];
  const RenderInput in = cached_render_input(kRoot + "/scenes/spheres.json");
  RenderOptions opt = input_options(in);
  opt.width = 48;
  opt.height = 36;
  const Geometry<fp24> g = load_geometry<fp24>(in.image);
  const LitParams<fp24> lp = lit_params<fp24>(opt.max_bounces, opt.background);
  const PacketSource<fp24> gen(opt.camera, opt.width, opt.height, opt.ray_source);

  // The packets, with the golden model's hits and counters per kind.
  struct Want {
    harness::CorePacket p;
    std::array<Hit<fp24>, kPacketRays> hits;
  };
  std::vector<Want> want;
  std::array<Counters, harness::kRayKinds> gold_kind{};
  Counters gold_total;
  const auto add = [&](harness::CorePacket p, const SecondaryLimits<fp24>* lim) {
    Want w{p, {}};
    Counters c;
    trace_packet(g, p.rays, p.mask, w.hits, c, lim);
    gold_kind[static_cast<size_t>(p.kind)].add(c);
    gold_total.add(c);
    want.push_back(w);
    return w.hits;
  };
  const auto secondary = [&](harness::RayKind kind, uint32_t mask,
                             const std::array<Ray<fp24>, kPacketRays>& rays,
                             const SecondaryLimits<fp24>& lim) {
    add(harness::secondary_packet(kind, mask, rays, lim, 0), &lim);  // slots set below
  };
  for (uint32_t py = 0; py < (opt.height + 1) / 2; ++py)
    for (uint32_t px = 0; px < (opt.width + 1) / 2; ++px) {
      harness::CorePacket p;
      p.mask = gen.packet(px, py, p.rays);
      const std::array<Hit<fp24>, kPacketRays> hits = add(p, nullptr);
      const LitWork<fp24> w = lit_work(g, p.rays, p.mask, hits, lp);
      for (const ShadowPacket<fp24>& sp : w.shadows)
        secondary(harness::RayKind::kShadow, sp.mask, sp.rays, sp.lim);
      if (w.bounce.mask)
        secondary(harness::RayKind::kBounce, w.bounce.mask, w.bounce.rays, w.bounce.lim);
      if (w.refract.mask)
        secondary(harness::RayKind::kRefract, w.refract.mask, w.refract.rays, w.refract.lim);
    }
  std::shuffle(want.begin(), want.end(), std::mt19937(26));
  std::vector<harness::CorePacket> packets;
  for (size_t j = 0; j < want.size(); ++j) {
    for (uint32_t r = 0; r < kPacketRays; ++r) want[j].p.slot[r] = static_cast<uint32_t>(4 * j + r);
    packets.push_back(want[j].p);
  }
  for (int k = 0; k < harness::kRayKinds; ++k)
    ASSERT_GT(gold_kind[static_cast<size_t>(k)].rays, 0u) << harness::ray_kind_name(k);

  CoreSimOptions so;
  so.stall_seed = mode.stall_seed;
  const CoreSimResult r = harness::trace_rtl(
      in.image, packets, 4, static_cast<uint32_t>(packets.size()), g.t_eps, so, mode.model);
  for (const std::string& p : harness::run_problems(r)) ADD_FAILURE() << p;
  uint64_t rays = 0, bad = 0;
  for (size_t j = 0; j < want.size(); ++j)
    for (uint32_t k = 0; k < kPacketRays; ++k) {
      if (!(want[j].p.mask >> k & 1u)) continue;
      ++rays;
      const size_t slot = 4 * j + k;
      const Hit<fp24>& h = want[j].hits[k];
      const HitRecord gh =
          h.tri >= 0 ? HitRecord{h.tri, h.t.bits(), h.u.bits(), h.v.bits()} : HitRecord{};
      std::array<uint8_t, 3> rgb{0, 0, 0};
      if (want[j].p.kind == harness::RayKind::kPrimary && h.tri >= 0)
        rgb = shade(g, want[j].p.rays[k], h);
      const HitRecord& rh = r.frame.hits[slot];
      const bool same = rh.tri == gh.tri && rh.t == gh.t && rh.u == gh.u && rh.v == gh.v &&
                        std::equal(rgb.begin(), rgb.end(), &r.frame.rgb[3 * slot]);
      if (!same && bad++ < 5)
        ADD_FAILURE() << harness::ray_kind_name(static_cast<int>(want[j].p.kind)) << " packet " << j
                      << " ray " << k << ": rtl " << hit_text(rh) << ", golden " << hit_text(gh);
    }
  for (const CounterDifference& d : counter_differences(gold_total, r.frame.counters))
    ADD_FAILURE() << "counter " << d.text();
  const auto kc = harness::kind_counters(r.perf);
  for (int k = 0; k < harness::kRayKinds; ++k) {
    const Counters& gk = gold_kind[static_cast<size_t>(k)];
    const harness::KindCounters& c = kc[static_cast<size_t>(k)];
    std::printf(
        "  %s: %llu rays, %llu traversal steps, %llu triangle tests (golden %llu, %llu, %llu)\n",
        harness::ray_kind_name(k).c_str(), static_cast<unsigned long long>(c.rays),
        static_cast<unsigned long long>(c.traversal_steps),
        static_cast<unsigned long long>(c.triangle_tests), static_cast<unsigned long long>(gk.rays),
        static_cast<unsigned long long>(gk.traversal_steps),
        static_cast<unsigned long long>(gk.triangle_tests));
    EXPECT_EQ(c.rays, gk.rays) << harness::ray_kind_name(k);
    EXPECT_EQ(c.traversal_steps, gk.traversal_steps) << harness::ray_kind_name(k);
    EXPECT_EQ(c.triangle_tests, gk.triangle_tests) << harness::ray_kind_name(k);
  }
  std::printf(
      "[cases] rtl mixed kinds %s: %llu cases, %llu mismatches (%llu packets, %llu cycles)\n",
      mode.name, static_cast<unsigned long long>(rays), static_cast<unsigned long long>(bad),
      static_cast<unsigned long long>(packets.size()), static_cast<unsigned long long>(r.cycles));
  EXPECT_EQ(bad, 0u);
}

// lat16, stall1, t1, t1_stall3 (kModes 0, 1, 3, 4).
std::string mode_name(const testing::TestParamInfo<int>& i) { return kModes[i.param].name; }

INSTANTIATE_TEST_SUITE_P(Modes, CoreRtlKinds, testing::Values(0, 1, 3, 4), mode_name);

//////////////////////////////////
// Corrupted images (errors)    //
//////////////////////////////////

// builtin:cornell with one record changed; the checksum is redone so the image loads.
class Corrupt {
 public:
  explicit Corrupt(const std::string& input = "builtin:cornell") {
    const RenderInput in =
        load_render_input(input, scene::LoadOptions{}, scene::NumberFormat::fp24());
    bytes_ = in.image.bytes();
    nodes_ = in.image.section(spec::kImageSectionIdNodes);
    lists_ = in.image.section(spec::kImageSectionIdLists);
    opt_ = input_options(in);
    opt_.width = 48;
    opt_.height = 36;
    opt_.progress = false;
  }
  scene::SceneImage image() const {
    std::vector<uint8_t> b = bytes_;
    scene::put_le(&b, spec::kImageHeaderChecksum, 0, 4);
    scene::put_le(&b, spec::kImageHeaderChecksum, scene::image_checksum(b), 4);
    return scene::SceneImage::from_bytes(std::move(b), "corrupted cornell");
  }
  scene::KdNode node(uint32_t i) const { return image().node(i); }
  void set_node(uint32_t i, scene::KdNode n) {
    scene::put_le(&bytes_, nodes_.offset + static_cast<size_t>(i) * nodes_.stride, n.raw, 8);
  }
  void set_list(uint32_t i, uint32_t v) {
    scene::put_le(&bytes_, lists_.offset + static_cast<size_t>(i) * lists_.stride, v, 4);
  }
  // An inner node at the given depth along the left spine (depth 0: the root).
  uint32_t inner_at(int depth) const {
    const scene::SceneImage img = image();
    uint32_t i = 0;
    for (int d = 0; d < depth; ++d) {
      const scene::KdNode n = img.node(i);
      if (n.is_leaf()) break;
      const scene::KdNode l = img.node(n.left());
      i = l.is_leaf() ? n.right() : n.left();
      if (img.node(i).is_leaf()) break;
    }
    EXPECT_FALSE(img.node(i).is_leaf());
    return i;
  }
  // The first leaf with at least `min_count` triangles.
  uint32_t leaf_with(uint32_t min_count) const {
    const scene::SceneImage img = image();
    for (uint32_t i = 0; i < img.node_count(); ++i)
      if (img.node(i).is_leaf() && img.node(i).count() >= min_count) return i;
    ADD_FAILURE() << "no leaf with " << min_count << " triangles";
    return 0;
  }

  RenderOptions& options() { return opt_; }

  void run(const std::string& what, uint32_t want_bits) const {
    const scene::SceneImage img = image();
    const Frame gold = render_golden(load_geometry<fp24>(img), opt_);
    EXPECT_GT(gold.counters.errors, 0u) << what << ": the corruption must be met";
    std::printf("%s: golden: %llu of %llu packets fail, error bits %u\n", what.c_str(),
                static_cast<unsigned long long>(gold.counters.errors),
                static_cast<unsigned long long>(gold.counters.packets), gold.counters.error_bits);
    EXPECT_EQ(gold.counters.error_bits, want_bits) << what;
    for (const Mode& mode : {kModes[0], kModes[1], kModes[3]}) {
      CoreSimOptions so;
      so.stall_seed = mode.stall_seed;
      so.watchdog_cycles = 50000;
      const CoreSimResult r = harness::render_rtl(img, opt_, so, mode.model);
      expect_bit_exact("corrupt " + what + " " + mode.name, gold, r);
      EXPECT_EQ(r.error_bits, want_bits) << what << " " << mode.name;
    }
  }

 private:
  std::vector<uint8_t> bytes_;
  scene::SectionInfo nodes_, lists_;
  RenderOptions opt_;
};

TEST(CoreRtlErrors, ChildPointingBackwards) {
  Corrupt c;
  const uint32_t i = c.inner_at(2);
  const scene::KdNode n = c.node(i);
  c.set_node(i, scene::KdNode::inner(n.axis(), i, n.split_bits()));  // left child = itself
  c.run("child pointing backwards", kErrMalformedNode);
}

TEST(CoreRtlErrors, ChildOutsideTheNodeSection) {
  Corrupt c;
  const uint32_t i = c.inner_at(1);
  const scene::KdNode n = c.node(i);
  const auto count = static_cast<uint32_t>(c.image().node_count());
  c.set_node(i, scene::KdNode::inner(n.axis(), count - 1, n.split_bits()));  // right child out
  c.run("child outside the node section", kErrMalformedNode);
}

TEST(CoreRtlErrors, NanSplit) {
  Corrupt c;
  const uint32_t i = c.inner_at(1);
  const scene::KdNode n = c.node(i);
  c.set_node(i, scene::KdNode::inner(n.axis(), n.left(), fp24::kQNaNBits));
  c.run("NaN split", kErrMalformedNode);
}

TEST(CoreRtlErrors, ListRangeOutOfBounds) {
  Corrupt c;
  const uint32_t i = c.leaf_with(2);
  const auto lists = static_cast<uint32_t>(c.image().list_size());
  c.set_node(i, scene::KdNode::leaf(lists - 1, c.node(i).count()));
  c.run("list range out of bounds", kErrBadAddress);
}

TEST(CoreRtlErrors, TriangleIndexOutOfBounds) {
  Corrupt c;
  const uint32_t i = c.leaf_with(2);
  const scene::KdNode n = c.node(i);
  c.set_list(n.first() + 1, c.image().triangle_count() + 7);  // the leaf's second entry
  std::printf("leaf %u: list entries %u .. %u, entry %u made out of bounds\n", i, n.first(),
              n.first() + n.count() - 1, n.first() + 1);
  c.run("triangle index out of bounds", kErrBadAddress);
}

// A tree deeper than the stack: inner nodes 0, 2, 4, ... split x ever closer to the box's upper
// x face, each with an empty leaf as its left child and the next inner node as its right child.
// Rays entering through that face and going towards -x (the camera looks along -x) have the right
// child as their near child and push the left leaf at every level until the stack overflows.
TEST(CoreRtlErrors, StackOverflow) {
  Corrupt c("builtin:spheres");
  const scene::SceneImage img = c.image();
  const auto b = img.bounds();
  constexpr uint32_t kLevels = static_cast<uint32_t>(spec::kKdtreeStackDepth) + 8;
  const auto count = static_cast<uint32_t>(img.node_count());
  ASSERT_GE(count, 2 * kLevels + 1);
  for (uint32_t i = 0; i < count; ++i) c.set_node(i, scene::KdNode::leaf(0, 0));
  const double w = b[3] - b[0];
  for (uint32_t k = 0; k < kLevels; ++k) {
    const double x = b[3] - w * std::ldexp(1.0, -static_cast<int>(k) - 1);
    c.set_node(2 * k, scene::KdNode::inner(0, 2 * k + 1, fp24::from_double(x).bits()));
  }
  const double cy = (b[1] + b[4]) / 2, cz = (b[2] + b[5]) / 2;
  c.options().camera.eye = glm::dvec3(b[3] + w, cy, cz);
  c.options().camera.look = glm::dvec3(b[0], cy, cz);
  c.options().camera.up = glm::dvec3(0, 1, 0);
  c.options().camera.fov_deg = 40;
  c.run("stack overflow", kErrStackOverflow);
}

}  // namespace
}  // namespace rc::test
