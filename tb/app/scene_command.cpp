// `raycore scene build` and `raycore scene info`.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.hpp"
#include "compiler.hpp"
#include "error.hpp"
#include "image.hpp"
#include "output_paths.hpp"
#include "scene.hpp"

namespace rc::app {
namespace {

using rc::scene::Error;

struct BuildOptions {
  std::string input;
  std::string output;
  std::string format = "7/16";
  std::vector<std::string> models_path;
  std::string stats_path;
  bool quiet = false;
};

void write_file(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(path + ": cannot write: " + std::strerror(errno));
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw Error(path + ": write failed: " + std::strerror(errno));
}

int run_build(const BuildOptions& o) {
  // The outputs before any work (each writable, neither the input nor the other output), and
  // again once the scene is loaded, against every file it was read from (meshes, MTL files).
  const std::vector<NamedPath> outputs = {{"-o", o.output}, {"--stats", o.stats_path}};
  const bool builtin = o.input.rfind("builtin:", 0) == 0;
  check_outputs(builtin ? std::vector<NamedPath>{} : std::vector<NamedPath>{{"input", o.input}},
                outputs);
  rc::scene::LoadOptions load;
  load.models_path = o.models_path;
  rc::scene::CompileOptions options;
  options.format = rc::scene::NumberFormat::parse(o.format);
  const auto t0 = std::chrono::steady_clock::now();
  const rc::scene::Scene scene = rc::scene::load_scene(o.input, load);
  const double load_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  check_outputs(scene_inputs(scene), outputs);
  rc::scene::Compiled c = rc::scene::compile_scene(scene, options);
  c.stats.load_ms = load_ms;
  for (const auto& w : c.stats.warnings) std::cerr << "raycore: warning: " << w << "\n";
  write_file(o.output, c.image);
  if (!o.stats_path.empty()) {
    const std::string text = rc::scene::stats_to_json(c.stats).dump(2) + "\n";
    write_file(o.stats_path, std::vector<uint8_t>(text.begin(), text.end()));
  }
  if (!o.quiet) {
    rc::scene::print_stats(std::cout, c.stats);
    std::cout << "wrote        " << o.output << "\n";
  }
  return 0;
}

std::string hex(uint32_t v, int digits) {
  std::ostringstream ss;
  ss << "0x" << std::hex << std::setw(digits) << std::setfill('0') << v;
  return ss.str();
}

int run_info(const std::string& path, bool validate) {
  const auto img = rc::scene::SceneImage::load(path);  // checks size, magic, version, checksum
  const auto& f = img.format();
  std::ostream& o = std::cout;
  o << "image        " << path << ", " << img.bytes().size() << " bytes\n";
  o << "version      " << img.version_major() << "." << img.version_minor() << "\n";
  o << "checksum     " << hex(img.checksum(), 8) << " (CRC-32, verified)\n";
  o << "format       " << f.name() << ", " << f.value_bytes() << " bytes per value\n";
  const auto b = img.bounds();
  o << std::setprecision(9);
  const auto bb = img.bounds_bits();
  o << "bounds       [" << b[0] << ", " << b[1] << ", " << b[2] << "] .. [" << b[3] << ", " << b[4]
    << ", " << b[5] << "]\n";
  o << "bounds bits ";
  for (uint32_t v : bb) o << " " << hex(v, (f.width() + 3) / 4);
  o << "\n";
  o << "triangles    " << img.triangle_count() << " (" << img.dropped_count()
    << " dropped as degenerate)\n";
  o << "kd-tree      root " << img.root_node() << ", " << img.node_count() << " nodes, "
    << img.list_size() << " list entries, depth " << img.tree_depth() << "\n";
  o << "materials    " << img.material_count();
  for (size_t i = 0; i < img.material_count() && i < 8; ++i)
    o << (i ? ", " : ": ") << img.material(i).name;
  if (img.material_count() > 8) o << ", ...";
  o << "\n";
  o << std::setprecision(6);
  const auto v = img.view();
  o << "view         " << v.width << "x" << v.height << ", eye (" << v.eye[0] << ", " << v.eye[1]
    << ", " << v.eye[2] << "), look (" << v.look[0] << ", " << v.look[1] << ", " << v.look[2]
    << "), fov " << v.fov_deg
    << ((v.flags & rc::spec::kImageViewFlagAutoCamera) ? " (automatic camera)" : "") << "\n";
  o << "lights       " << img.light_count() << "\n";
  o << "sections     id  name           offset        bytes      count  stride\n";
  for (const auto& s : img.sections())
    o << "             " << std::setw(2) << s.id << "  " << std::left << std::setw(10)
      << rc::scene::section_name(s.id) << std::right << std::setw(11) << s.offset << std::setw(13)
      << s.bytes << std::setw(11) << s.count << std::setw(8) << s.stride << "\n";
  if (!validate) return 0;
  const rc::scene::Validation checked = img.validation();
  if (checked.ok()) {
    o << "validate     tree and records well formed\n";
    return 0;
  }
  for (const auto& p : checked.problems) std::cerr << "raycore: malformed: " << p << "\n";
  const size_t total = checked.total, listed = checked.problems.size();
  const std::string count = total == 1 ? "1 problem" : std::to_string(total) + " problems";
  throw Error(path + ": the image is malformed (" + count +
              (total == listed ? std::string(total == 1 ? ", listed above)" : ", all listed above)")
                               : ", the first " + std::to_string(listed) + " listed above)"));
}

}  // namespace

void add_scene_commands(CLI::App& app, Action* action) {
  CLI::App* scene =
      app.add_subcommand("scene", "Compile scenes into memory images and inspect them");
  scene->require_subcommand(1);

  auto build = std::make_shared<BuildOptions>();
  CLI::App* b = scene->add_subcommand(
      "build", "Compile an OBJ file, a scene.json or builtin:NAME into a memory image");
  b->add_option("input", build->input,
                "OBJ file, scene .json file, or builtin:NAME (cornell, spheres, terrain)")
      ->required();
  b->add_option("-o,--output", build->output, "The image file to write")->required();
  b->add_option("--format", build->format, "Number format EXP/FRAC: 7/16 (fp24) or 8/23 (fp32)")
      ->check([](const std::string& s) {
        try {
          (void)rc::scene::NumberFormat::parse(s);
          return std::string();
        } catch (const Error& e) {
          return std::string(e.what());
        }
      });
  b->add_option("--models-path", build->models_path,
                "Directories to search for mesh files (':' separates several; also "
                "RAYCORE_MODELS_PATH)");
  b->add_option("--stats", build->stats_path, "Also write the build statistics as JSON here");
  b->add_flag("-q,--quiet", build->quiet, "Do not print the statistics");
  b->callback([build, action] { *action = [build] { return run_build(*build); }; });

  auto info_path = std::make_shared<std::string>();
  auto no_validate = std::make_shared<bool>(false);
  CLI::App* i = scene->add_subcommand(
      "info", "Print an image's header, sections, format, bounds and counts; verify it");
  i->add_option("image", *info_path, "The image file")->required();
  i->add_flag("--no-validate", *no_validate, "Skip walking the tree and records");
  i->callback([info_path, no_validate, action] {
    *action = [info_path, no_validate] { return run_info(*info_path, !*no_validate); };
  });
}

}  // namespace rc::app
