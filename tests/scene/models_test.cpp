// Every model of ../shared/models (the .obj files its README lists) and every scene in scenes/
// builds into a sound, well-formed image.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "compiler.hpp"
#include "error.hpp"
#include "test_util.hpp"

namespace rc::test {
namespace {

using rc::scene::CompileOptions;
using rc::scene::SceneImage;

void build_and_check(const rc::scene::Scene& scene, const std::string& what) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto c = rc::scene::compile_scene(scene, CompileOptions());
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const SceneImage img = SceneImage::from_bytes(c.image, what);
  const auto problems = img.validate();
  for (const auto& p : problems) ADD_FAILURE() << what << ": " << p;
  const TreeCheck t = check_tree(img, scene_triangles(scene));
  for (const auto& p : t.problems) ADD_FAILURE() << what << ": " << p;
  EXPECT_EQ(t.missing, 0u);
  EXPECT_EQ(t.nodes, img.node_count());
  EXPECT_LE(t.depth, static_cast<uint32_t>(rc::spec::kKdtreeMaxDepth));
  std::cout << what << ": " << c.stats.triangles << " triangles (" << c.stats.dropped
            << " dropped), " << c.stats.nodes << " nodes, depth " << c.stats.depth << ", SAH "
            << c.stats.sah_cost << ", compile " << ms << " ms\n";
  report_cases(what + " (triangle, overlapped leaf) pairs listed", t.pairs, t.missing);
}

std::vector<std::string> model_params() {
  std::vector<std::string> names = readme_models();
  if (names.empty()) names.push_back("(models directory absent)");
  return names;
}

std::string param_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string s = info.param;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

class SharedModel : public ::testing::TestWithParam<std::string> {};

TEST_P(SharedModel, Builds) {
  const std::string dir = models_dir();
  if (dir.empty())
    GTEST_SKIP() << "../shared/models is absent (expected beside the repository): nothing to build";
  const std::string path = dir + "/" + GetParam();
  ASSERT_TRUE(std::filesystem::exists(path)) << "listed in README.md but missing: " << path;
  rc::scene::LoadOptions none;
  build_and_check(rc::scene::load_scene(path, none), GetParam());
}

INSTANTIATE_TEST_SUITE_P(Models, SharedModel, ::testing::ValuesIn(model_params()), param_name);

TEST(SharedModels, ReadmeListsModels) {
  if (models_dir().empty()) GTEST_SKIP() << "../shared/models is absent";
  // The README lists 16 models, among them the three of the benchmark.
  const auto names = readme_models();
  EXPECT_GE(names.size(), 16u);
  for (const char* want : {"bunny/bunny.obj", "sponza/sponza.obj", "conference/conference.obj"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
}

std::vector<std::string> scene_params() {
  std::vector<std::string> out;
  for (const auto& p : repo_scenes()) out.push_back(std::filesystem::path(p).filename().string());
  return out;
}

class RepoScene : public ::testing::TestWithParam<std::string> {};

TEST_P(RepoScene, Builds) {
  const std::string path = std::string(RC_SOURCE_DIR) + "/scenes/" + GetParam();
  rc::scene::Scene scene;
  try {
    scene = rc::scene::load_scene(path, {});
  } catch (const rc::scene::Error& e) {
    if (models_dir().empty() && std::string(e.what()).find("not found") != std::string::npos)
      GTEST_SKIP() << "needs ../shared/models: " << e.what();
    throw;
  }
  ASSERT_TRUE(scene.camera.has_value()) << "every scene in scenes/ places its camera";
  build_and_check(scene, "scenes/" + GetParam());
}

INSTANTIATE_TEST_SUITE_P(Scenes, RepoScene, ::testing::ValuesIn(scene_params()), param_name);

TEST(RepoScenes, DefaultSceneIsTheCornellBox) {
  const auto scene = rc::scene::load_scene(std::string(RC_SOURCE_DIR) + "/scenes/default.json", {});
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].source, "builtin:cornell");
  EXPECT_EQ(scene.width, 256u);
  EXPECT_EQ(scene.height, 192u);
  EXPECT_GE(scene_params().size(), 6u);
}

}  // namespace
}  // namespace rc::test
