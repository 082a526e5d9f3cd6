// OBJ/MTL loading: fan triangulation in file order, materials, scene files, and every input error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include "compiler.hpp"
#include "error.hpp"
#include "image.hpp"
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
  // MTL numbers are the loader's checked, correctly rounded values (tinyobjloader's own are not
  // always correctly rounded in the last bit of a double); the tolerance is from when they were.
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
  EXPECT_EQ(red.transmit(), 0.0);
  EXPECT_NEAR(lamp.transmit(), 0.5, 1e-12) << "1 - d; Tf counts only for illum 4, 6, 7";
  EXPECT_NEAR(m.materials[2].transmit(), 0.75, 1e-12) << "1 - d (Tr 0.75), Tf 0";
}

// The refraction weight: max(1 - d, Tf's largest channel for illum 4, 6, 7), at most 1.
TEST(Obj, TransmitWeight) {
  rc::scene::Material m;
  EXPECT_EQ(m.transmit(), 0.0) << "the default material is opaque";
  m.tf = {0.2, 0.9, 0.4};
  EXPECT_EQ(m.transmit(), 0.0) << "illum 2 has no refraction";
  for (int illum : {4, 6, 7}) {
    m.illum = illum;
    EXPECT_EQ(m.transmit(), 0.9) << illum;
  }
  m.illum = 5;
  EXPECT_EQ(m.transmit(), 0.0) << "illum 5 reflects only";
  m.illum = 7;
  m.dissolve = 0.05;
  EXPECT_EQ(m.transmit(), 1.0 - 0.05) << "1 - d is larger";
  m.tf = {3.0, 0.0, 0.0};
  EXPECT_EQ(m.transmit(), 1.0) << "clamped";
}

TEST(Obj, MissingMtlIsAWarning) {
  const Mesh m = rc::scene::parse_obj("mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                                      "w.obj", temp_dir());
  EXPECT_FALSE(m.warnings.empty());
  EXPECT_EQ(m.triangles.size(), 1u);
}

TEST(Obj, MissingMtlWarningNamesTheFile) {
  const Mesh m = rc::scene::parse_obj(
      "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n", "g.obj", temp_dir());
  bool named = false;
  for (const auto& w : m.warnings)
    named =
        named || w.find("cannot open MTL file " + temp_dir() + "/gone.mtl") != std::string::npos;
  EXPECT_TRUE(named) << ::testing::PrintToString(m.warnings);
  EXPECT_TRUE(m.material_files.empty());
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].name, "(default)");
}

const std::string kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// Loads an OBJ that uses `mtl` (written as NAME.mtl in the temporary directory).
Mesh with_mtl(const std::string& name, const std::string& mtl) {
  write_temp(name + ".mtl", mtl);
  return rc::scene::parse_obj("mtllib " + name + ".mtl\n" + kTri, name + ".obj", temp_dir());
}

TEST(Mtl, BadValuesNameFileLineAndField) {
  struct Case {
    std::string mtl;
    std::string expect;  // after "DIR/bad.mtl:"
  };
  const std::vector<Case> cases = {
      {"newmtl a\nKd banana -1 1e40\n", "2: Kd: 'banana' is not a number"},
      {"newmtl a\nKd 0.5 -1 0.5\n", "2: Kd: -1 is negative (colours are 0 or more)"},
      {"newmtl a\nKd 1 1 1e40\n",
       "2: Kd: 1e40 is too large: the largest fp24 (7/16) value is 1.84466033e+19"},
      {"newmtl a\nKs 0 0 1e999\n", "2: Ks: 1e999 is too large"},
      {"newmtl a\nKe inf 0 0\n", "2: Ke: 'inf' is not a finite number"},
      {"newmtl a\nTf 1 1 1x\n", "2: Tf: '1x' is not a number"},
      {"newmtl a\nKt -1 0 0\n", "2: Kt: -1 is negative"},
      {"newmtl a\nKa -0.5\n", "2: Ka: -0.5 is negative"},
      {"newmtl a\nKs 0.5 0.5\n", "2: Ks: expected 3 numbers r g b (or 1 number for grey), got 2"},
      {"newmtl a\nKs 0.5 0.5 0.5 0.5\n",
       "2: Ks: expected 3 numbers r g b (or 1 number for grey), got 4"},
      {"newmtl a\nKd\n", "2: Kd: expected 3 numbers r g b (or 1 number for grey), got 0"},
      {"newmtl a\nKd spectral red.rfl\n", "2: Kd: the 'spectral' form is not supported"},
      {"newmtl a\nNs -5\n", "2: Ns: -5 is negative (it must be 0 or more)"},
      {"newmtl a\nNs 10abc\n", "2: Ns: '10abc' is not a number"},
      {"newmtl a\nNs\n", "2: Ns: expected a number, got nothing"},
      {"newmtl a\nNs 10 x\n", "2: Ns: expected one number, got 'Ns 10 x' ('x' is not a number)"},
      {"newmtl a\nNs 1e40\n", "2: Ns: 1e40 is too large"},
      {"newmtl a\nd 7\n", "2: d: 7 is outside [0, 1]"},
      {"newmtl a\nd -0.5\n", "2: d: -0.5 is outside [0, 1]"},
      {"newmtl a\nTr 1.5\n", "2: Tr: 1.5 is outside [0, 1]"},
      {"newmtl a\nillum 99\n", "2: illum: '99' is not an integer in 0..10"},
      {"newmtl a\nillum 2.5\n", "2: illum: '2.5' is not an integer in 0..10"},
      {"newmtl a\nillum -1\n", "2: illum: '-1' is not an integer in 0..10"},
      {"newmtl a\nNi nan\n", "2: Ni: 'nan' is not a finite number"},
      {"newmtl a\nNi 0\n", "2: Ni: 0 is not greater than 0"},
      {"newmtl a\nNi -1.5\n", "2: Ni: -1.5 is not greater than 0"},
      {"newmtl a\nNi 1e-30\n", "2: Ni: 1e-30 is too small: the smallest fp24 (7/16) value is"},
      {"newmtl\n", "1: newmtl without a material name"},
      // Line numbers count CRLF and lone CR line ends, comments and blank lines.
      {"# c\r\n\r\nnewmtl a\r\n  Kd 1 1 1 # ok\r\n\tKs 0 0 -0.5\r\n", "5: Ks: -0.5 is negative"},
      {"newmtl a\rNs 1\rNi 1.5\rd -1\r", "4: d: -1 is outside [0, 1]"},
      // A value before the first newmtl is checked too; so is every material, not just the first.
      {"Kd -1 0 0\nnewmtl a\n", "1: Kd: -1 is negative"},
      {"newmtl a\nKd 1 1 1\nnewmtl b\nKd 1 1 1\nillum 11\n", "5: illum: '11' is not an integer"},
  };
  size_t mismatches = 0;
  for (const auto& c : cases) {
    const std::string err = error_of([&] { with_mtl("bad", c.mtl); });
    const std::string want = temp_dir() + "/bad.mtl:" + c.expect;
    const bool ok = err.find(want) == 0;
    mismatches += !ok;
    EXPECT_TRUE(ok) << ::testing::PrintToString(c.mtl) << ": expected '" << want << "', got '"
                    << err << "'";
  }
  report_cases("malformed MTL values", cases.size(), mismatches);
}

TEST(Mtl, GreyCommentsExtraNumbersAndDissolve) {
  const Mesh m = with_mtl("ok",
                          "newmtl grey\nKd 0.5\nKs 0.25 # one number: grey\nKe 0.1 0.2 0.3 # rgb\n"
                          "newmtl tr\nTr 0.25\n"
                          "newmtl tr_then_d\nTr 0.3\nd 0.5\n"
                          "newmtl d_then_tr\nd 0.5\nTr 0.3\n"
                          "newmtl teapot\n  Tr 0  0\n  illum 10\n  Ni 1e-3\n  Ns 0\n");
  ASSERT_EQ(m.materials.size(), 6u);  // five, and the default for the face without usemtl
  const auto& grey = m.materials[0];
  EXPECT_EQ(grey.kd, glm::dvec3(0.5));
  EXPECT_EQ(grey.ks, glm::dvec3(0.25));
  EXPECT_EQ(grey.ke, glm::dvec3(0.1, 0.2, 0.3));  // correctly rounded, exactly
  EXPECT_EQ(m.materials[1].dissolve, 0.75);
  EXPECT_EQ(m.materials[2].dissolve, 0.5);  // d wins in either order
  EXPECT_EQ(m.materials[3].dissolve, 0.5);
  EXPECT_EQ(m.materials[4].dissolve, 1.0);
  EXPECT_EQ(m.materials[4].illum, 10);
  EXPECT_EQ(m.materials[4].ior, 1e-3);
  ASSERT_EQ(m.material_files.size(), 1u);
  EXPECT_EQ(m.material_files[0], temp_dir() + "/ok.mtl");
  // "Tr 0  0" (as in the shared teapot's MTL) is a warning naming the line, not an error.
  const std::string want =
      temp_dir() + "/ok.mtl:14: Tr: 2 numbers where one is expected; the first is used";
  EXPECT_NE(std::find(m.warnings.begin(), m.warnings.end(), want), m.warnings.end())
      << ::testing::PrintToString(m.warnings);
  // The checked values reach the image: Kd 0.5 grey in every channel.
  const auto c = rc::scene::compile_scene(scene_of(m), CompileOptions());
  const auto img = rc::scene::SceneImage::from_bytes(c.image);
  const auto rec = img.material(0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(img.format().decode(rec.kd[k]), 0.5) << k;
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

// Missing keys, colours, intensities, light positions and cameras: the whole message, from the
// file name on, so that the path of the key is checked too.
TEST(SceneJson, ValuesAndMissingKeys) {
  const std::string box = R"({"meshes": [{"builtin": "cornell"}], )";
  const std::string view = R"("eye": [0, 0, 5], "look": [0, 0, 0])";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {box + R"("camera": {"look": [0, 0, 0]}})",
       "j.json: camera.eye: missing (this key is required)"},
      {box + R"("camera": {"eye": [0, 0, 5]}})",
       "j.json: camera.look: missing (this key is required)"},
      {box + R"("camera": [1, 2]})", "j.json: camera: expected a JSON object"},
      {box + R"("background": [-0.1, 0, 0]})",
       "j.json: background: r = -0.1 is outside [0, 1] (colours are fractions per channel, 1 = "
       "255)"},
      {box + R"("background": [0, 2, 0]})", "j.json: background: g = 2 is outside [0, 1]"},
      {box + R"("background": [0, 0, 1e300]})", "j.json: background: b = 1e+300 is outside [0, 1]"},
      {box + R"("background": [0, 0, 1e999]})", "j.json: invalid JSON:"},
      {box + R"("lights": [{"position": [0, 1, 0], "color": [1, -1, 1]}]})",
       "j.json: lights[0].color: g = -1 is outside [0, 1]"},
      {box + R"("lights": [{"position": [0, 1, 0], "color": [1, 1, 255]}]})",
       "j.json: lights[0].color: b = 255 is outside [0, 1]"},
      {box + R"("lights": [{"position": [0, 1, 0]}, {"position": [0, 1, 0], "intensity": -2}]})",
       "j.json: lights[1].intensity: -2 is outside [0, 1000000]"},
      {box + R"("lights": [{"position": [0, 1, 0], "intensity": 1e30}]})",
       "j.json: lights[0].intensity: 1e+30 is outside [0, 1000000]"},
      {box + R"("lights": [{"position": [0, 1, 0], "intensity": "bright"}]})",
       "j.json: lights[0].intensity: expected a number"},
      {box + R"("lights": [{"position": [0, 1e39, 0]}]})",
       "j.json: lights[0].position: y = 1e+39 is outside the float32 range (|x| <= "
       "3.40282347e+38; the image stores it as float32)"},
      {box + R"("lights": [{"type": "directional", "direction": [1e-50, 0, 0]}]})",
       "j.json: lights[0].direction: must not be zero (as float32, as the image stores it)"},
      // The camera rule (shared with render): fov, parallel and zero up vectors, float32.
      {box + R"("camera": {)" + view + R"(, "fov": 1e-300}})",
       "j.json: camera.fov: 1e-300 degrees is outside [0.001, 179.999] (the vertical field of "
       "view, in degrees)"},
      {box + R"("camera": {)" + view + R"(, "fov": 180}})", "j.json: camera.fov: 180 degrees"},
      {box + R"("camera": {)" + view + R"(, "fov": 0}})", "j.json: camera.fov: 0 degrees"},
      {box + R"("camera": {)" + view + R"(, "up": [0, 1e-12, 1]}})",
       "j.json: camera.up: is parallel to the view direction: the sine of the angle between them "
       "is 1e-12, it must be at least 0.0001"},
      {box + R"("camera": {)" + view + R"(, "up": [0, 0, -3]}})",
       "j.json: camera.up: is parallel to the view direction"},
      {box + R"("camera": {)" + view + R"(, "up": [0, 0, 0]}})",
       "j.json: camera.up: must not be zero"},
      {box + R"("camera": {)" + view + R"(, "up": [0, 1e-50, 0]}})",
       "j.json: camera.up: must not be zero once rounded to float32 (the image stores float32)"},
      {box + R"("camera": {"eye": [1, 0, 0], "look": [1.0000000001, 0, 0]}})",
       "j.json: camera.look: must differ from eye once rounded to float32"},
      {box + R"("camera": {"eye": [0, 0, 1e39], "look": [0, 0, 0]}})",
       "j.json: camera.eye: z = 1e+39 is outside the float32 range"},
  };
  size_t mismatches = 0;
  for (const auto& [text, expect] : cases) {
    const std::string err =
        error_of([&] { rc::scene::load_scene_json_text(text, "j.json", temp_dir(), {}); });
    const bool ok = err.find(expect) == 0;
    mismatches += !ok;
    EXPECT_TRUE(ok) << text << ": expected '" << expect << "', got '" << err << "'";
  }
  report_cases("scene JSON values and missing keys", cases.size(), mismatches);
}

TEST(SceneJson, CameraRuleIsScaleFree) {
  // A tiny up vector that is not parallel to the view is as good as a unit one; so are a tiny
  // view distance and the extreme fovs.
  const std::string box = R"({"meshes": [{"builtin": "cornell"}], "camera": )";
  for (const std::string cam :
       {R"({"eye": [0, 0, 5], "look": [0, 0, 0], "up": [0, 1e-12, 0]})",
        R"({"eye": [0, 0, 5], "look": [0, 0, 0], "up": [1e-30, 1e-30, 0], "fov": 0.001})",
        R"({"eye": [0, 0, 1e-30], "look": [0, 0, 0], "up": [0, 1, 0], "fov": 179.999})",
        R"({"eye": [0, 10, 0], "look": [0, 0, 0], "up": [0, 1, 0.001]})"}) {
    rc::scene::Scene s;
    EXPECT_NO_THROW(s = rc::scene::load_scene_json_text(box + cam + "}", "j.json", "", {})) << cam;
    ASSERT_TRUE(s.camera.has_value()) << cam;
    EXPECT_FALSE(rc::scene::camera_problem(*s.camera).has_value()) << cam;
  }
  // The library function directly: the messages name the field.
  rc::scene::Camera c;
  c.eye = {0, 0, 5};
  c.up = {0, 1e-12, 1};
  EXPECT_EQ(error_of([&] { rc::scene::check_camera(c); }).rfind("camera.up: is parallel", 0), 0u);
  c.up = {0, 1e-12, 0};
  EXPECT_NO_THROW(rc::scene::check_camera(c));
  c.fov_deg = 1e-300;
  EXPECT_EQ(error_of([&] {
              rc::scene::check_camera(c, "x.json: camera");
            }).rfind("x.json: camera.fov: 1e-300 degrees is outside", 0),
            0u);
  c.fov_deg = std::nan("");
  EXPECT_TRUE(rc::scene::camera_problem(c).has_value());
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
