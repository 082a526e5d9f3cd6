// The raycore executable: exit status 0 on success, 1 for errors (with a message naming the file
// and the problem), 2 for usage errors; never a crash or a hang.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "compiler.hpp"
#include "test_util.hpp"

namespace rc::test {
namespace {

std::vector<uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
}

void write_file(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

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
  for (const char* want : {"version      1.0", "verified", "fp24 (7/16)", "bounds",
                           "triangles    32", "nodes", "well formed"})
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
      {"OBJ given to info", {"scene", "info", dir + "/bad.obj"}, 1, "truncated image"},
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
}

}  // namespace
}  // namespace rc::test
