// `raycore render` and `raycore board-image` on bad input, run as a user runs them: each case of
// the tables below is a command line with its expected exit status (1: an error while running, 2: a
// usage error) and a fragment of the message, and must write nothing (its output directory stays
// empty) and leave its inputs as they were. The scene commands' cases are in scene_cli_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "compiler.hpp"
#include "fp.hpp"
#include "image.hpp"
#include "rc_constants.hpp"
#include "scene.hpp"
#include "test_util.hpp"

namespace rc::test {
namespace {

namespace fs = std::filesystem;
using rc::scene::KdNode;
using rc::scene::SceneImage;

const std::string kRoot = RC_SOURCE_DIR;

// The default scene (it has a light) compiled at fp24.
const std::vector<uint8_t>& default_image() {
  static const std::vector<uint8_t> bytes = [] {
    const auto s = rc::scene::load_scene(kRoot + "/scenes/default.json", {});
    return rc::scene::compile_scene(s, {}).image;
  }();
  return bytes;
}

struct Case {
  std::string name;
  std::vector<std::string> args;  // OUT in an argument stands for the case's output directory
  int status;
  std::string expect;
};

// Runs every case with a fresh, empty output directory; checks status, message, that the
// directory is still empty and that every file of `inputs` is unchanged.
void run_cases(const std::string& what, const std::vector<Case>& cases,
               const std::vector<std::string>& inputs) {
  std::vector<std::vector<uint8_t>> before;
  for (const auto& p : inputs) before.push_back(read_file(p));
  size_t mismatches = 0, n = 0;
  for (const Case& c : cases) {
    const std::string out = temp_dir() + "/out" + std::to_string(n++);
    fs::remove_all(out);
    fs::create_directories(out);
    std::vector<std::string> args;
    for (std::string a : c.args) {
      for (size_t at; (at = a.find("OUT")) != std::string::npos;) a.replace(at, 3, out);
      args.push_back(a);
    }
    const RunResult r = run_raycore(args);
    const bool status_ok = r.status == c.status;
    const bool text_ok = r.output.find(c.expect) != std::string::npos;
    const bool empty_ok = fs::is_empty(out);
    const bool ok = status_ok && text_ok && empty_ok;
    mismatches += !ok;
    std::string cmd = "raycore";
    for (const auto& a : args) cmd += " " + a;
    EXPECT_TRUE(ok) << c.name << ": " << cmd << "\n  expected status " << c.status << " and '"
                    << c.expect << "'" << (empty_ok ? "" : ", and nothing written")
                    << "; got status " << r.status << ":\n"
                    << r.output;
  }
  for (size_t i = 0; i < inputs.size(); ++i)
    EXPECT_EQ(read_file(inputs[i]), before[i]) << inputs[i] << " was changed";
  report_cases(what, cases.size(), mismatches);
}

TEST(RenderCli, BadOptionsAndOutputs) {
  const std::string dir = temp_dir();
  const std::string scene = dir + "/scene.json";
  fs::copy_file(kRoot + "/scenes/default.json", scene, fs::copy_options::overwrite_existing);
  const std::string img = dir + "/good.rcimg";
  write_file(img, default_image());
  fs::create_directories(dir + "/a_directory");
  // A mesh with its MTL file, and a scene file naming the mesh: both are inputs of a render.
  write_temp("tri.obj", "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  write_temp("tri.mtl", "newmtl red\nKd 1 0 0\n");
  write_temp("tri.json", R"({"meshes": [{"path": "tri.obj"}]})");
  const std::string obj = dir + "/tri.obj", mtl = dir + "/tri.mtl", tri_scene = dir + "/tri.json";
  // The default scene with five lights: one more than the tree controller holds.
  const std::string img5 = dir + "/five_lights.rcimg";
  {
    scene::Scene s5 = scene::load_scene(kRoot + "/scenes/default.json", {});
    while (s5.lights.size() < static_cast<size_t>(spec::kLightMaxLights) + 1)
      s5.lights.push_back(s5.lights.front());
    write_file(img5, scene::compile_scene(s5, {}).image);
  }
  const std::string png = "OUT/x.png";
  const std::vector<std::string> rtl = {"render", img, "--engine", "rtl", "--size", "4x4", "-q"};
  const auto with = [](std::vector<std::string> base, std::vector<std::string> more) {
    base.insert(base.end(), more.begin(), more.end());
    return base;
  };
  const std::vector<Case> cases = {
      // Numbers on the command line.
      {"threads too many", {"render", img, "-o", png, "--threads", "100000"}, 2, "--threads"},
      {"threads negative", {"render", img, "-o", png, "--threads", "-1"}, 2, "--threads"},
      {"watchdog 0", with(rtl, {"-o", png, "--watchdog", "0"}), 2, "--watchdog"},
      {"stall seed -1", with(rtl, {"-o", png, "--stall-seed", "-1"}), 2, "--stall-seed"},
      {"stall seed with text", with(rtl, {"-o", png, "--stall-seed", "7x"}), 2, "--stall-seed"},
      {"latency 0", with(rtl, {"-o", png, "--latency", "0"}), 2, "--latency"},
      {"size 0x4", {"render", img, "-o", png, "--size", "0x4"}, 1, "--size"},
      {"size with text", {"render", img, "-o", png, "--size", "4x4px"}, 1, "--size"},
      {"fov with a unit",
       {"render", img, "-o", png, "--camera", "eye=0,1,3:look=0,1,0:fov=45deg"},
       1,
       "fov has a bad number '45deg'"},
      {"threads-rtl 7", with(rtl, {"-o", png, "--threads-rtl", "7"}), 1, "--threads-rtl"},
      {"setup-units-rtl 3", with(rtl, {"-o", png, "--setup-units-rtl", "3"}), 1,
       "--setup-units-rtl: expected 1, 2 or default, got '3'"},
      {"two model options", with(rtl, {"-o", png, "--threads-rtl", "1", "--setup-units-rtl", "2"}),
       1, "--threads-rtl 1 and --setup-units-rtl 2: no core model has both"},
      {"setup-units-rtl with golden",
       {"render", img, "-o", png, "--setup-units-rtl", "1"},
       1,
       "--setup-units-rtl needs --engine rtl"},
      {"unknown engine", {"render", img, "-o", png, "--engine", "gpu"}, 1, "--engine"},
      {"unknown lighting",
       {"render", img, "-o", png, "--lighting", "sun"},
       1,
       "unknown lighting 'sun' (headlight, scene)"},
      {"five lights on the lit board",
       {"render", img5, "--engine", "board", "--size", "4x4", "-q", "-o", png, "--lighting",
        "scene"},
       1,
       "the lit board holds 4 lights, the scene has 5"},
      {"board-image bounces beyond the limit",
       {"board-image", img, "-o", "OUT/b", "--lighting", "scene", "--bounces", "9"},
       2,
       "--bounces"},
      {"board-image five lights",
       {"board-image", img5, "-o", "OUT/b", "--size", "4x4", "--lighting", "scene"},
       1,
       "the lit board holds 4 lights, the scene has 5"},
      {"unknown secondary", with(rtl, {"-o", png, "--lighting", "scene", "--secondary", "gpu"}), 1,
       "--secondary: expected chip or host, got 'gpu'"},
      {"secondary with the headlight", with(rtl, {"-o", png, "--secondary", "host"}), 1,
       "--secondary needs --lighting scene"},
      {"secondary with golden",
       {"render", img, "-o", png, "--lighting", "scene", "--secondary", "host"},
       1,
       "--secondary needs --engine rtl"},
      {"on chip around a core without a tracer",
       with(rtl, {"-o", png, "--lighting", "scene", "--threads-rtl", "16"}), 1,
       "the tree controller (rc_tracer) is built around the default core and the core with one "
       "thread only, not this model (trace them on the host: --secondary host)"},
      {"on chip with five lights",
       {"render", img5, "--engine", "rtl", "--size", "4x4", "-q", "-o", png, "--lighting", "scene"},
       1,
       "the tree controller holds 4 lights ([light] max_lights), "},
      {"bounces beyond the limit",
       {"render", img, "-o", png, "--lighting", "scene", "--bounces", "9"},
       1,
       "--bounces: at most 8, got 9"},
      {"bounces with the headlight",
       {"render", img, "-o", png, "--bounces", "2"},
       1,
       "--bounces needs --lighting scene"},
      {"negative bounces",
       {"render", img, "-o", png, "--lighting", "scene", "--bounces", "-1"},
       2,
       "--bounces: expected a whole number of decimal digits, got '-1'"},
      {"check with golden", {"render", img, "-o", png, "--check"}, 1, "--check needs"},
      {"diff without reference",
       {"render", img, "-o", png, "--diff", "OUT/d.png"},
       1,
       "--diff needs"},
      {"trace with golden",
       {"render", img, "-o", png, "--trace", "OUT/t.fst"},
       1,
       "--trace needs --engine rtl"},
      {"latency with golden",
       {"render", img, "-o", png, "--latency", "4"},
       1,
       "--latency needs --engine rtl"},
      {"stall seed with board",
       {"render", img, "-o", png, "--engine", "board", "--stall-seed", "3"},
       1,
       "--stall-seed needs --engine rtl"},
      {"trace window without trace", with(rtl, {"-o", png, "--trace-window", "1:5"}), 1,
       "--trace-window needs --trace"},
      {"trace window backwards",
       with(rtl, {"-o", png, "--trace", "OUT/t.fst", "--trace-window", "5:3"}), 1,
       "--trace-window: expected FIRST:LAST"},
      // Outputs, checked before the render.
      {"trace in a missing directory", with(rtl, {"-o", png, "--trace", "/no/such/dir/t.fst"}), 1,
       "--trace /no/such/dir/t.fst: cannot write: the directory /no/such/dir does not exist"},
      {"output in a missing directory",
       {"render", img, "-o", "/no/such/dir/x.png"},
       1,
       "-o /no/such/dir/x.png: cannot write"},
      {"hits in a missing directory",
       {"render", img, "-o", png, "--hits", "/no/such/dir/x.hits"},
       1,
       "--hits /no/such/dir/x.hits: cannot write"},
      {"stats in a missing directory",
       {"render", img, "-o", png, "--stats", "/no/such/dir/s.json"},
       1,
       "--stats /no/such/dir/s.json: cannot write"},
      {"output is a directory",
       {"render", img, "-o", dir + "/a_directory"},
       1,
       "it is a directory"},
      {"output and hits the same file",
       {"render", img, "-o", "OUT/x.ppm", "--hits", "OUT/x.ppm"},
       1,
       "are the same file"},
      {"stats and output the same file (other spelling)",
       {"render", img, "-o", "OUT/x.png", "--stats", "OUT/./x.png"},
       1,
       "are the same file"},
      {"output is the input scene",
       {"render", scene, "-o", scene},
       1,
       "refusing to overwrite an input"},
      {"stats is the input image",
       {"render", img, "-o", png, "--stats", img},
       1,
       "refusing to overwrite an input"},
      {"hits is the OBJ's MTL file",
       {"render", obj, "-o", png, "--hits", mtl},
       1,
       "--hits " + mtl + ": is the MTL file"},
      {"stats is the scene's mesh",
       {"render", tri_scene, "-o", png, "--stats", obj},
       1,
       "--stats " + obj + ": is the mesh"},
      {"output format unknown", {"render", img, "-o", "OUT/x.nosuchformat"}, 1, "no image format"},
      {"check's difference image unwritable",
       with(rtl, {"-o", png, "--check", "--diff", "/no/such/dir/d.png"}), 1,
       "--diff /no/such/dir/d.png: cannot write"},
      {"trace window after the frame",
       with(rtl, {"-o", png, "--trace", "OUT/t.fst", "--trace-window", "900000000:900000001"}), 1,
       "no waveform written"},
      // board-image.
      {"board-image fb-pixels huge",
       {"board-image", img, "-o", "OUT/b", "--fb-pixels", "4000000000"},
       2,
       "--fb-pixels"},
      {"board-image fb-pixels 0",
       {"board-image", img, "-o", "OUT/b", "--fb-pixels", "0"},
       2,
       "--fb-pixels"},
      {"board-image into a file", {"board-image", img, "-o", img}, 1, "is not a directory"},
      {"board-image under a file",
       {"board-image", img, "-o", img + "/sub"},
       1,
       "is not a directory"},
  };
  run_cases("raycore render/board-image options and outputs", cases,
            {scene, img, obj, mtl, tri_scene});
}

// A malformed memory image is refused by every engine and by board-image, naming the problem,
// before any work: the checks of `raycore scene info`.
TEST(RenderCli, MalformedImagesRefusedByEveryEngine) {
  const std::string dir = temp_dir();
  const SceneImage good = SceneImage::from_bytes(default_image());
  ASSERT_TRUE(good.validate().empty());
  ASSERT_GT(good.light_count(), 0u);
  const auto& nodes = good.section(spec::kImageSectionIdNodes);
  const auto& shading = good.section(spec::kImageSectionIdShading);
  const auto& lights = good.section(spec::kImageSectionIdLights);
  size_t inner = 0, leaf = 0;
  for (size_t i = 0; i < good.node_count(); ++i) {
    if (!good.node(i).is_leaf()) inner = i;
    if (good.node(i).is_leaf() && good.node(i).count() > 0) leaf = i;
  }
  const KdNode in = good.node(inner), lf = good.node(leaf);
  const auto node_at = [&](size_t i) { return nodes.offset + i * spec::kKdNodeBytes; };
  const auto bound = [](int i) { return spec::kImageHeaderBoundsValue + 4 * i; };
  const auto bb = good.bounds_bits();
  struct Bad {
    std::string name;
    std::function<void(std::vector<uint8_t>*)> apply;
    std::string expect;
  };
  const std::vector<Bad> bad = {
      {"node cycle",
       [&](auto* b) {
         patch(b, node_at(inner),
               KdNode::inner(in.axis(), static_cast<uint32_t>(inner), in.split_bits()).raw, 8);
       },
       "is not after the node"},
      {"leaf range outside the lists",
       [&](auto* b) {
         patch(b, node_at(leaf),
               KdNode::leaf(lf.first(), static_cast<uint32_t>(good.list_size() + 1)).raw, 8);
       },
       "exceeds the list section"},
      {"NaN bounds", [&](auto* b) { patch(b, bound(0), rc::fp24::nan().bits(), 4); },
       "bounds value 0 is not finite"},
      {"inverted bounds",
       [&](auto* b) {
         patch(b, bound(1), bb[4], 4);
         patch(b, bound(4), bb[1], 4);
       },
       "bounds: min > max on axis 1"},
      {"bad light type", [&](auto* b) { patch(b, lights.offset + spec::kImageLightType, 7, 4); },
       "light 0: unknown type 7"},
      {"material out of range", [&](auto* b) { patch(b, shading.offset, 77, 4); },
       "material 77 out of range"},
  };
  const std::vector<std::vector<std::string>> commands = {
      {"render", "IMG", "-o", "OUT/x.png", "--size", "8x8", "-q"},
      {"render", "IMG", "-o", "OUT/x.png", "--size", "8x8", "-q", "--engine", "rtl", "--check"},
      {"render", "IMG", "-o", "OUT/x.png", "--size", "8x8", "-q", "--engine", "board"},
      {"board-image", "IMG", "-o", "OUT/board", "--size", "8x8"},
  };
  std::vector<Case> cases;
  std::vector<std::string> inputs;
  for (const Bad& b : bad) {
    std::vector<uint8_t> bytes = default_image();
    b.apply(&bytes);
    fix_checksum(&bytes);
    std::string file = b.name;
    for (char& ch : file)
      if (ch == ' ') ch = '_';
    file = dir + "/" + file + ".rcimg";
    write_file(file, bytes);
    inputs.push_back(file);
    for (const auto& cmd : commands) {
      Case c{b.name + ", " + cmd[0] + (cmd.size() > 8 ? " " + cmd[8] : ""), cmd, 1,
             "the image is malformed"};
      for (auto& a : c.args)
        if (a == "IMG") a = file;
      cases.push_back(c);
      c.name += " (names the problem)";
      c.expect = b.expect;
      cases.push_back(c);
    }
  }
  run_cases("raycore render/board-image malformed images", cases, inputs);
}

}  // namespace
}  // namespace rc::test
