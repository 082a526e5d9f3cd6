// `raycore scene build` and `raycore scene info` run as a process: exit status 0 on success, 1 for
// errors (with a message naming the file and the problem), 2 for usage errors; never a crash or a
// hang, nothing written on an error. render and board-image: render_cli_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <nlohmann/json.hpp>

#include "compiler.hpp"
#include "image.hpp"
#include "test_util.hpp"

namespace rc::test {
namespace {

TEST(Cli, BuildAndInfo) {
  const std::string img = temp_dir() + "/cli.rcimg", stats = temp_dir() + "/cli.json";
  const RunResult b =
      run_raycore({"scene", "build", "builtin:cornell", "-o", img, "--stats", stats});
  ASSERT_EQ(b.status, 0) << b.output;
  for (const char* want :
       {"triangles", "kd-tree", "SAH cost", "depth", "sections", "CRC-32", "kd-tree build"})
    EXPECT_NE(b.output.find(want), std::string::npos) << want << "\n" << b.output;
  std::ifstream in(stats);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["triangles"], 32);
  EXPECT_GT(j["kdtree"]["nodes"].get<int>(), 1);
  EXPECT_TRUE(j["kdtree"].contains("mean_triangles_per_nonempty_leaf"));
  const RunResult i = run_raycore({"scene", "info", img});
  ASSERT_EQ(i.status, 0) << i.output;
  const std::string version = "version      " + std::to_string(rc::spec::kImageVersionMajor) + "." +
                              std::to_string(rc::spec::kImageVersionMinor);
  for (const std::string& want :
       {version, std::string("verified"), std::string("fp24 (7/16)"), std::string("bounds"),
        std::string("triangles    32"), std::string("nodes"), std::string("well formed")})
    EXPECT_NE(i.output.find(want), std::string::npos) << want << "\n" << i.output;
  const RunResult f =
      run_raycore({"scene", "build", "builtin:cornell", "-o", img, "--format", "8/23", "-q"});
  ASSERT_EQ(f.status, 0) << f.output;
  EXPECT_TRUE(f.output.empty()) << f.output;
  EXPECT_NE(run_raycore({"scene", "info", img}).output.find("fp32 (8/23)"), std::string::npos);
  // scenes/default.json, as the README's main command builds it.
  const RunResult d = run_raycore(
      {"scene", "build", std::string(RC_SOURCE_DIR) + "/scenes/default.json", "-o", img, "-q"});
  EXPECT_EQ(d.status, 0) << d.output;
}

struct BadRun {
  std::string name;
  std::vector<std::string> args;
  int status;
  std::string expect;
};

TEST(Cli, ErrorsAndUsage) {
  const std::string dir = temp_dir();
  const std::string good = dir + "/good.rcimg";
  ASSERT_EQ(run_raycore({"scene", "build", "builtin:cornell", "-o", good, "-q"}).status, 0);
  const auto bytes = read_file(good);
  auto truncated = bytes;
  truncated.resize(bytes.size() / 2);
  write_file(dir + "/truncated.rcimg", truncated);
  auto magic = bytes;
  magic[0] ^= 0xff;
  write_file(dir + "/magic.rcimg", magic);
  auto version = bytes;
  version[rc::spec::kImageHeaderVersionMajor] = 9;
  fix_checksum(&version);
  write_file(dir + "/version.rcimg", version);
  auto corrupt = bytes;
  corrupt[bytes.size() / 2] ^= 1;
  write_file(dir + "/corrupt.rcimg", corrupt);
  write_temp("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
  write_temp("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  write_temp("empty.obj", "# nothing\n");
  write_temp("nan.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n");
  write_temp("bad.json", "{\"meshes\": 3}");
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string self = write_temp("self.obj", tri);
  const std::string with_mtl = write_temp("withmtl.obj", "mtllib withmtl.mtl\n" + tri);
  const std::string mtl = write_temp("withmtl.mtl", "newmtl a\nKd 0.5 0.5 0.5\n");
  write_temp("badmtl.obj", "mtllib badmtl.mtl\n" + tri);
  write_temp("badmtl.mtl", "newmtl a\nKd banana -1 1e40\n");
  const std::string mesh = write_temp("mesh.obj", tri);
  const std::string scene = write_temp("scene.json", R"({"meshes": [{"path": "mesh.obj"}]})");
  write_temp("fov.json",
             R"({"meshes": [{"builtin": "cornell"}],
                 "camera": {"eye": [0, 0, 5], "look": [0, 0, 0], "fov": 1e-300}})");
  write_temp("up.json", R"({"meshes": [{"builtin": "cornell"}],
                 "camera": {"eye": [0, 0, 5], "look": [0, 0, 0], "up": [0, 1e-12, 1]}})");
  write_temp("noeye.json",
             R"({"meshes": [{"builtin": "cornell"}], "camera": {"look": [0, 0, 0]}})");
  write_temp("thirtytwo.bin", std::string(32, 'x'));
  write_temp("three.bin", "RCI");
  // An image with 32 problems: every shading record names a material beyond the table.
  auto many = bytes;
  {
    const auto img = rc::scene::SceneImage::from_bytes(bytes);
    const auto& sh = section_of(img, rc::spec::kImageSectionIdShading);
    ASSERT_EQ(img.triangle_count(), 32u);
    ASSERT_EQ(img.dropped_count(), 0u);
    for (uint32_t t = 0; t < img.triangle_count(); ++t)
      patch(&many, sh.offset + t * sh.stride + rc::spec::kImageShadingMaterial, 1000 + t, 4);
    fix_checksum(&many);
    const auto v = rc::scene::SceneImage::from_bytes(many).validation();
    EXPECT_EQ(v.total, 32u);
    EXPECT_EQ(v.problems.size(), 20u);
  }
  write_file(dir + "/many.rcimg", many);
  const std::string out = dir + "/out.rcimg";
  const std::vector<BadRun> cases = {
      {"no arguments", {}, 2, "subcommand"},
      {"unknown subcommand", {"frobnicate"}, 2, "subcommand"},
      {"scene without subcommand", {"scene"}, 2, "subcommand"},
      {"build without output", {"scene", "build", "builtin:cornell"}, 2, "--output"},
      {"bad format",
       {"scene", "build", "builtin:cornell", "-o", out, "--format", "6/10"},
       2,
       "unsupported number format 6/10"},
      {"missing OBJ",
       {"scene", "build", dir + "/missing.obj", "-o", out},
       1,
       "missing.obj: mesh file not found"},
      {"missing scene",
       {"scene", "build", dir + "/missing.json", "-o", out},
       1,
       "missing.json: cannot open"},
      {"malformed OBJ",
       {"scene", "build", dir + "/bad.obj", "-o", out},
       1,
       "bad.obj:4: malformed face line"},
      {"index out of range",
       {"scene", "build", dir + "/range.obj", "-o", out},
       1,
       "range.obj:4: face vertex index 4"},
      {"empty mesh",
       {"scene", "build", dir + "/empty.obj", "-o", out},
       1,
       "empty.obj: the mesh is empty"},
      {"NaN coordinate",
       {"scene", "build", dir + "/nan.obj", "-o", out},
       1,
       "nan.obj: triangle 0 (face on line 4): vertex 2 coordinate z = nan"},
      {"bad scene file", {"scene", "build", dir + "/bad.json", "-o", out}, 1, "bad.json: meshes"},
      {"unknown builtin",
       {"scene", "build", "builtin:teapot", "-o", out},
       1,
       "unknown built-in scene"},
      {"unwritable output",
       {"scene", "build", "builtin:cornell", "-o", "/nonexistent/x.rcimg"},
       1,
       "/nonexistent/x.rcimg: cannot write"},
      {"info of a missing image",
       {"scene", "info", dir + "/none.rcimg"},
       1,
       "none.rcimg: cannot open"},
      {"truncated image", {"scene", "info", dir + "/truncated.rcimg"}, 1, "truncated image"},
      {"wrong magic", {"scene", "info", dir + "/magic.rcimg"}, 1, "not a raycore image"},
      {"wrong version",
       {"scene", "info", dir + "/version.rcimg"},
       1,
       "unsupported image version 9"},
      {"checksum mismatch", {"scene", "info", dir + "/corrupt.rcimg"}, 1, "checksum mismatch"},
      {"OBJ given to info", {"scene", "info", dir + "/bad.obj"}, 1, "not a raycore image"},
      {"32-byte non-image given to info",
       {"scene", "info", dir + "/thirtytwo.bin"},
       1,
       "thirtytwo.bin: not a raycore image: magic 0x78787878"},
      {"3-byte file given to info", {"scene", "info", dir + "/three.bin"}, 1, "truncated image"},
      {"image with 32 problems",
       {"scene", "info", dir + "/many.rcimg"},
       1,
       "many.rcimg: the image is malformed (32 problems, the first 20 listed above)"},
      {"image with 32 problems: the 21st line",
       {"scene", "info", dir + "/many.rcimg"},
       1,
       "raycore: malformed: triangle 19: material 1019 out of range (4 materials)\nraycore: "
       "error:"},
      {"output is the input",
       {"scene", "build", self, "-o", self},
       1,
       "-o " + self + ": is the input " + self + ": refusing to overwrite an input"},
      {"--stats is -o",
       {"scene", "build", "builtin:cornell", "-o", out, "--stats", out},
       1,
       "--stats " + out + " and -o " + out + " are the same file"},
      {"--stats is the input",
       {"scene", "build", self, "-o", out, "--stats", self},
       1,
       "--stats " + self + ": is the input"},
      {"output in a missing directory",
       {"scene", "build", "builtin:cornell", "-o", dir + "/no/such/dir/x.rcimg"},
       1,
       "-o " + dir + "/no/such/dir/x.rcimg: cannot write: the directory " + dir +
           "/no/such/dir does not exist"},
      {"output is the OBJ's MTL file",
       {"scene", "build", with_mtl, "-o", mtl},
       1,
       "-o " + mtl + ": is the MTL file " + mtl + ": refusing to overwrite an input"},
      {"output is a JSON scene's mesh",
       {"scene", "build", scene, "-o", mesh},
       1,
       "-o " + mesh + ": is the mesh " + mesh + ": refusing to overwrite an input"},
      {"bad MTL value",
       {"scene", "build", dir + "/badmtl.obj", "-o", out},
       1,
       "raycore: error: " + dir + "/badmtl.mtl:2: Kd: 'banana' is not a number"},
      {"camera fov too small",
       {"scene", "build", dir + "/fov.json", "-o", out},
       1,
       "fov.json: camera.fov: 1e-300 degrees is outside [0.001, 179.999]"},
      {"camera up parallel to the view",
       {"scene", "build", dir + "/up.json", "-o", out},
       1,
       "up.json: camera.up: is parallel to the view direction"},
      {"camera without eye",
       {"scene", "build", dir + "/noeye.json", "-o", out},
       1,
       "noeye.json: camera.eye: missing (this key is required)"},
      {"render --camera with trailing text",
       {"render", "builtin:cornell", "--engine", "golden", "-o", dir + "/r.png", "--camera",
        "eye=0,1,3.8:look=0,1,0:fov=45deg"},
       1,
       "camera: fov has a bad number '45deg'"},
      {"render --camera up parallel to the view",
       {"render", "builtin:cornell", "--engine", "golden", "-o", dir + "/r.png", "--camera",
        "eye=0,0,5:look=0,0,0:up=0,1e-12,1"},
       1,
       "camera.up: is parallel to the view direction"},
  };
  size_t mismatches = 0;
  for (const auto& c : cases) {
    const RunResult r = run_raycore(c.args);
    const bool ok = r.status == c.status && r.output.find(c.expect) != std::string::npos;
    mismatches += !ok;
    EXPECT_TRUE(ok) << c.name << ": expected status " << c.status << " and '" << c.expect
                    << "', got status " << r.status << ":\n"
                    << r.output;
  }
  report_cases("raycore command line errors", cases.size(), mismatches);
  // Nothing was written: no output appeared, and no input was overwritten.
  for (const std::string& f : {out, dir + "/r.png"}) EXPECT_FALSE(std::filesystem::exists(f)) << f;
  EXPECT_EQ(read_file(self), std::vector<uint8_t>(tri.begin(), tri.end()));
  const std::string mtl_text = "newmtl a\nKd 0.5 0.5 0.5\n";
  EXPECT_EQ(read_file(mtl), std::vector<uint8_t>(mtl_text.begin(), mtl_text.end()));
  EXPECT_EQ(read_file(mesh), std::vector<uint8_t>(tri.begin(), tri.end()));
}

}  // namespace
}  // namespace rc::test
