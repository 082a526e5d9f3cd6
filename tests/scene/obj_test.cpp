// OBJ/MTL loading: fan triangulation in file order, materials, scene files, and every input error.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "compiler.hpp"
#include "error.hpp"
#include "test_util.hpp"

namespace rc::test {
namespace {

using rc::scene::CompileOptions;
using rc::scene::Error;
using rc::scene::Mesh;
using rc::scene::NumberFormat;
using rc::scene::Scene;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

Scene scene_of(Mesh m) {
  Scene s;
  s.source = m.source;
  s.meshes.push_back(std::move(m));
  return s;
}

TEST(Obj, FanTriangulationInFileOrder) {
  // Groups, objects and material switches interleave; faces keep file order across all of them.
  const std::string obj =
      "# test\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\nv 0.5 2 0\n"
      "g a\n"
      "f 1 2 3 4\n"  // quad: (1 2 3) (1 3 4)
      "o obj\n"
      "f 1 2 3\n"  // triangle
      "g b\n"
      "usemtl none\n"
      "f 1/1 2/2 3/3 4/4 5/5\n"  // pentagon: (1 2 3) (1 3 4) (1 4 5)
      "g a\r\n"                  // group a again, CRLF line ending
      "f -6//1 -5//1 -1//1\r\n"  // relative indices: (1 2 6)
      "f 6 5 4 3 2 1\n";         // hexagon: (6 5 4) (6 4 3) (6 3 2) (6 2 1)
  const Mesh m = rc::scene::parse_obj(obj, "fan.obj", temp_dir());
  const std::vector<std::array<uint32_t, 3>> want = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 1, 2},
                                                     {0, 2, 3}, {0, 3, 4}, {0, 1, 5}, {5, 4, 3},
                                                     {5, 3, 2}, {5, 2, 1}, {5, 1, 0}};
  ASSERT_EQ(m.triangles.size(), want.size());
  size_t bad = 0;
  for (size_t i = 0; i < want.size(); ++i) {
    bad += m.triangles[i] != want[i];
    EXPECT_EQ(m.triangles[i], want[i]) << "triangle " << i;
  }
  report_cases("fan triangulation order", want.size(), bad);
  const std::vector<uint32_t> lines = {9, 9, 11, 14, 14, 14, 16, 17, 17, 17, 17};
  EXPECT_EQ(m.line, lines);
  EXPECT_EQ(m.vertices.size(), 6u);
  EXPECT_EQ(m.vertices[4], glm::dvec3(-1, 0.5, 0));
  // No MTL: every face uses the appended default material.
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].name, "(default)");
  for (uint32_t mat : m.material) EXPECT_EQ(mat, 0u);
}

TEST(Obj, CoordinatesAreCorrectlyRounded) {
  const Mesh m = rc::scene::parse_obj(
      "v 0.1 -1.5e-3 +2\nv 123456.789012345678 1E2 .5\nv 0 0 1 1 0 0\nf 1 2 3\n", "num.obj", ".");
  EXPECT_EQ(m.vertices[0], glm::dvec3(0.1, -1.5e-3, 2.0));
  EXPECT_EQ(m.vertices[1], glm::dvec3(123456.789012345678, 100.0, 0.5));
  EXPECT_EQ(m.vertices[2], glm::dvec3(0, 0, 1));
}

TEST(Obj, MaterialsFromMtl) {
  write_temp("m.mtl",
             "newmtl red\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 20\nillum 3\n"
             "newmtl lamp\nKd 1 1 1\nKe 10 9 8\nd 0.5\nNi 1.5\nTf 0.1 0.2 0.3\nillum 2\n"
             "newmtl glass\nTr 0.75\nillum 7\n");
  const std::string obj =
      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "f 1 2 3\nusemtl lamp\nf 1 2 3\nusemtl red\nf 1 2 3\nusemtl glass\nf 1 2 3\n";
  const std::string path = write_temp("m.obj", obj);
  const Mesh m = rc::scene::load_obj(path);
  ASSERT_EQ(m.materials.size(), 4u);  // red, lamp, glass, (default)
  EXPECT_EQ(m.material, (std::vector<uint32_t>{3, 1, 0, 2}));
  // MTL numbers are parsed by tinyobjloader (not always correctly rounded in the last bit of a
  // double, which the rounding to the image's format makes irrelevant).
  const auto near = [](const glm::dvec3& a, const glm::dvec3& b) {
    return std::abs(a.x - b.x) < 1e-12 && std::abs(a.y - b.y) < 1e-12 &&
           std::abs(a.z - b.z) < 1e-12;
  };
  const auto& red = m.materials[0];
  EXPECT_EQ(red.name, "red");
  EXPECT_TRUE(near(red.kd, {0.8, 0.1, 0.1}));
  EXPECT_TRUE(near(red.ks, glm::dvec3(0.5)));
  EXPECT_NEAR(red.ns, 20.0, 1e-12);
  EXPECT_EQ(red.illum, 3);
  EXPECT_NEAR(red.mirror(), 0.5, 1e-12);
  const auto& lamp = m.materials[1];
  EXPECT_TRUE(near(lamp.ke, {10, 9, 8}));
  EXPECT_NEAR(lamp.dissolve, 0.5, 1e-12);
  EXPECT_NEAR(lamp.ior, 1.5, 1e-12);
  EXPECT_TRUE(near(lamp.tf, {0.1, 0.2, 0.3}));
  EXPECT_EQ(lamp.mirror(), 0.0);
  EXPECT_NEAR(m.materials[2].dissolve, 0.25, 1e-12);
  EXPECT_EQ(m.materials[2].illum, 7);
}

TEST(Obj, MissingMtlIsAWarning) {
  const Mesh m = rc::scene::parse_obj("mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                                      "w.obj", temp_dir());
  EXPECT_FALSE(m.warnings.empty());
  EXPECT_EQ(m.triangles.size(), 1u);
}

struct BadObj {
  std::string name, text, expect;
};

TEST(Obj, InputErrors) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::vector<BadObj> cases = {
      {"vertex with two coordinates", "v 1 2\n", "bad.obj:1: malformed vertex line"},
      {"vertex with a word", tri + "v 1 abc 3\n", "bad.obj:4: malformed vertex line"},
      {"vertex with too many numbers", "v 1 2 3 4 5 6 7 8\n", "bad.obj:1: malformed vertex line"},
      {"face with a word", tri + "f 1 2 x\n", "bad.obj:4: malformed face line"},
      {"face with trailing junk", tri + "f 1 2 3abc\n", "bad.obj:4: malformed face line"},
      {"face with two vertices", tri + "f 1 2\n", "bad.obj:4: malformed face line"},
      {"face with index 0", tri + "f 0 1 2\n", "bad.obj:4: malformed face line"},
      {"face with a bad normal index", tri + "f 1//0 2//1 3//1\n",
       "bad.obj:4: malformed face line"},
      {"face with an empty reference", tri + "f 1/ 2 3\n", "bad.obj:4: malformed face line"},
      {"face index beyond the vertices", tri + "f 1 2 9\n",
       "bad.obj:4: face vertex index 9 is out of range"},
      {"relative index before the first vertex", tri + "f -1 -2 -4\n",
       "bad.obj:4: face vertex index -4 is out of range"},
      {"no faces", tri, "bad.obj: the mesh is empty"},
      {"empty file", "", "bad.obj: the mesh is empty"},
      {"binary garbage", std::string("v 1 2 3\n\0\x01\x02", 11), "NUL byte"},
  };
  size_t mismatches = 0;
  for (const auto& c : cases) {
    const std::string err = error_of([&] { rc::scene::parse_obj(c.text, "bad.obj", "."); });
    const bool ok = err.find(c.expect) != std::string::npos;
    mismatches += !ok;
    EXPECT_TRUE(ok) << c.name << ": expected '" << c.expect << "', got '" << err << "'";
  }
  report_cases("malformed OBJ inputs", cases.size(), mismatches);
  const std::string missing = error_of([] { rc::scene::load_obj("/nonexistent/dir/x.obj"); });
  EXPECT_NE(missing.find("/nonexistent/dir/x.obj: cannot open OBJ file"), std::string::npos)
      << missing;
  rc::scene::LoadOptions none;
  const std::string not_found = error_of([&] { rc::scene::load_scene("no/such/model.obj", none); });
  EXPECT_NE(not_found.find("no/such/model.obj: mesh file not found"), std::string::npos)
      << not_found;
}

TEST(Obj, BadCoordinatesNameTheTriangleAndFile) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n", "coordinate y = nan is not a finite number"},
      {"v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", "coordinate x = inf is not a finite number"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 -1e999\nf 1 2 3\n", "coordinate z = -inf is not a finite number"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 3e19\nf 1 2 3\nf 2 3 4\n",
       "triangle 1 (face on line 6): vertex 4 coordinate z = 3e+19 is outside the fp24 (7/16) "
       "range"},
  };
  size_t mismatches = 0;
  for (const auto& [text, expect] : cases) {
    const Mesh m = rc::scene::parse_obj(text, "coords.obj", ".");
    const std::string err =
        error_of([&] { rc::scene::compile_scene(scene_of(m), CompileOptions()); });
    const bool ok = err.find(expect) != std::string::npos && err.find("coords.obj: triangle") == 0;
    mismatches += !ok;
    EXPECT_TRUE(ok) << "expected '" << expect << "', got '" << err << "'";
  }
  report_cases("NaN, infinite and out-of-range coordinates", cases.size(), mismatches);
  // A NaN vertex that no face uses is harmless; 3e19 fits fp32.
  const Mesh unused =
      rc::scene::parse_obj("v nan 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 2 3 4\n", "u.obj", ".");
  EXPECT_NO_THROW(rc::scene::compile_scene(scene_of(unused), CompileOptions()));
  CompileOptions fp32;
  fp32.format = NumberFormat::fp32();
  const Mesh big = rc::scene::parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 3e19\nf 1 2 3\n", "b.obj", ".");
  EXPECT_NO_THROW(rc::scene::compile_scene(scene_of(big), fp32));
  // Everything degenerate.
  const Mesh flat = rc::scene::parse_obj("v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n", "flat.obj", ".");
  const std::string err =
      error_of([&] { rc::scene::compile_scene(scene_of(flat), CompileOptions()); });
  EXPECT_NE(err.find("all 1 triangles are degenerate"), std::string::npos) << err;
}

TEST(SceneJson, ParsesAllFields) {
  write_temp("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string json = R"({
    "name": "t", "description": "test",
    "meshes": [{"path": "tri.obj", "transform": {"scale": 2, "rotate": [0, 90, 0], "translate": [1, 2, 3]}},
               {"builtin": "spheres", "params": {"count": 1}}],
    "camera": {"eye": [0, 0, 5], "look": [0, 0, 0], "up": [0, 1, 0], "fov": 30},
    "resolution": [64, 48], "background": [0.1, 0.2, 0.3],
    "lights": [{"type": "point", "position": [1, 2, 3], "color": [1, 1, 1], "intensity": 2},
               {"type": "directional", "direction": [0, -1, 0]}]
  })";
  const Scene s = rc::scene::load_scene_json_text(json, "t.json", temp_dir(), {});
  EXPECT_EQ(s.name, "t");
  ASSERT_EQ(s.meshes.size(), 2u);
  // scale 2, rotate 90 degrees about y (x -> -z), translate (1, 2, 3): (1, 0, 0) -> (1, 2, 1).
  EXPECT_NEAR(s.meshes[0].vertices[1].x, 1.0, 1e-12);
  EXPECT_NEAR(s.meshes[0].vertices[1].y, 2.0, 1e-12);
  EXPECT_NEAR(s.meshes[0].vertices[1].z, 1.0, 1e-12);
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_EQ(s.camera->fov_deg, 30.0);
  EXPECT_EQ(s.width, 64u);
  EXPECT_EQ(s.height, 48u);
  EXPECT_EQ(s.background, glm::dvec3(0.1, 0.2, 0.3));
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].intensity, 2.0);
  EXPECT_EQ(s.lights[1].type, rc::scene::Light::Type::kDirectional);
  // The two meshes become one image, triangles numbered over both.
  const auto c = rc::scene::compile_scene(s, CompileOptions());
  EXPECT_EQ(c.stats.triangles, 1 + s.meshes[1].triangles.size());
}

TEST(SceneJson, Errors) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{", "j.json: invalid JSON"},
      {"[]", "j.json: expected a JSON object"},
      {R"({"meshes": []})", "meshes: expected a non-empty array"},
      {R"({"meshes": [{"builtin": "cornell"}], "camra": {}})", "camra: unknown key"},
      {R"({"meshes": [{"builtin": "nope"}]})", "unknown built-in scene 'builtin:nope'"},
      {R"({"meshes": [{"path": "missing.obj"}]})", "missing.obj: mesh file not found"},
      {R"({"meshes": [{"path": "a.obj", "builtin": "cornell"}]})", "exactly one of"},
      {R"({"meshes": [{"builtin": "cornell"}], "camera": {"eye": [0, 0], "look": [0, 0, 1]}})",
       "camera.eye: expected an array of 3 numbers"},
      {R"({"meshes": [{"builtin": "cornell"}], "camera": {"eye": [0, 0, 0], "look": [0, 0, 0]}})",
       "camera.look: must differ from eye"},
      {R"({"meshes": [{"builtin": "cornell"}], "resolution": [0, 10]})", "resolution: expected"},
      {R"({"meshes": [{"builtin": "cornell"}], "lights": [{"type": "spot"}]})", "lights[0].type"},
      {R"({"meshes": [{"builtin": "terrain", "params": {"grid": -1}}]})", "parameter 'grid'"},
  };
  size_t mismatches = 0;
  for (const auto& [text, expect] : cases) {
    const std::string err =
        error_of([&] { rc::scene::load_scene_json_text(text, "j.json", temp_dir(), {}); });
    const bool ok = err.find(expect) != std::string::npos;
    mismatches += !ok;
    EXPECT_TRUE(ok) << text << ": expected '" << expect << "', got '" << err << "'";
  }
  report_cases("scene JSON errors", cases.size(), mismatches);
}

TEST(SceneJson, ModelSearchPath) {
  const std::string dir = temp_dir() + "/models";
  std::filesystem::create_directories(dir + "/sub");
  write_temp("models/sub/found.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  rc::scene::LoadOptions opt;
  opt.models_path = {"/nonexistent:" + dir};
  EXPECT_EQ(rc::scene::find_model("sub/found.obj", "", opt), dir + "/sub/found.obj");
  setenv("RAYCORE_MODELS_PATH", dir.c_str(), 1);
  EXPECT_EQ(rc::scene::find_model("sub/found.obj", "", {}), dir + "/sub/found.obj");
  unsetenv("RAYCORE_MODELS_PATH");
  const auto search = rc::scene::model_search_path({});
  ASSERT_GE(search.size(), 2u);
  EXPECT_EQ(search[search.size() - 2], "../shared/models");
  EXPECT_EQ(search.back(), rc::scene::source_root() + "/../shared/models");
}

}  // namespace
}  // namespace rc::test
