// `raycore render`: render a scene with the golden model or the Embree reference.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.hpp"
#include "compare.hpp"
#include "embree_engine.hpp"
#include "error.hpp"
#include "geometry.hpp"
#include "job.hpp"

namespace rc::app {
namespace {

using rc::scene::Error;

struct RenderArgs {
  std::string input, output, hits, stats, diff, size, camera, engine = "golden", reference;
  std::string format = "7/16";
  std::vector<std::string> models_path;
  bool auto_camera = false, quiet = false;
  unsigned threads = 0;
};

void parse_size(const std::string& text, uint32_t& w, uint32_t& h) {
  unsigned long a = 0, b = 0;
  char x = 0, extra = 0;
  std::istringstream ss(text);
  if (!(ss >> a >> x >> b) || (x != 'x' && x != 'X') || (ss >> extra) || a == 0 || b == 0 ||
      a > 16384 || b > 16384)
    throw Error("--size: expected WxH with 1 <= W, H <= 16384, got '" + text + "'");
  w = static_cast<uint32_t>(a);
  h = static_cast<uint32_t>(b);
}

nlohmann::json counters_json(const Counters& c) {
  const auto per_packet = [&](uint64_t v) {
    return c.packets ? static_cast<double>(v) / static_cast<double>(c.packets) : 0.0;
  };
  nlohmann::json means = {{"nodes_fetched", per_packet(c.nodes_fetched)},
                          {"traversal_steps", per_packet(c.traversal_steps)},
                          {"leaf_visits", per_packet(c.leaf_visits)},
                          {"list_entries", per_packet(c.list_entries)},
                          {"triangle_tests", per_packet(c.triangle_tests)}};
  nlohmann::json totals = {{"packets", c.packets},
                           {"rays", c.rays},
                           {"nodes_fetched", c.nodes_fetched},
                           {"inner_visits", c.inner_visits},
                           {"traversal_steps", c.traversal_steps},
                           {"leaf_visits", c.leaf_visits},
                           {"empty_leaf_visits", c.empty_leaves},
                           {"list_entries", c.list_entries},
                           {"triangle_tests", c.triangle_tests},
                           {"stack_pushes", c.stack_pushes},
                           {"stack_pops", c.stack_pops},
                           {"culled_pops", c.culled_pops},
                           {"max_stack", c.max_stack},
                           {"failed_packets", c.errors},
                           {"error_bits", c.error_bits}};
  totals["per_packet_mean"] = means;
  return totals;
}

template <class T>
Frame run_engine(const std::string& engine, const RenderInput& in, const RenderOptions& opt) {
  if (engine == "golden") return render_golden(load_geometry<T>(in.image), opt);
  if (!in.scene)
    throw Error(
        "--engine embree needs the scene's triangles: give the scene or OBJ file, not "
        "the memory image '" +
        in.name + "'");
  return render_embree<T>(triangle_soup(*in.scene), opt);
}

Frame run_any(const std::string& engine, const RenderInput& in, const RenderOptions& opt) {
  if (in.image.format().is<fp24>()) return run_engine<fp24>(engine, in, opt);
  if (in.image.format().is<fp32ftz>()) return run_engine<fp32ftz>(engine, in, opt);
  throw Error(in.name + ": no engine for the number format " + in.image.format().name());
}

int run_render(const RenderArgs& a) {
  if (a.engine != "golden" && a.engine != "embree")
    throw Error("--engine: expected golden or embree, got '" + a.engine + "'");
  if (!a.reference.empty() && a.reference != "embree" && a.reference != "golden")
    throw Error("--reference: expected embree or golden, got '" + a.reference + "'");
  scene::LoadOptions load;
  load.models_path = a.models_path;
  const RenderInput in = load_render_input(a.input, load, scene::NumberFormat::parse(a.format));
  RenderOptions opt = input_options(in);
  if (!a.size.empty()) parse_size(a.size, opt.width, opt.height);
  if (!a.camera.empty()) opt.camera = parse_camera(a.camera);
  if (a.auto_camera) opt.camera = auto_camera_for(in.image);
  opt.threads = a.threads;
  opt.progress = !a.quiet;

  const Frame f = run_any(a.engine, in, opt);
  write_image(a.output, f.width, f.height, f.rgb);
  if (!a.hits.empty()) write_hits(a.hits, f);

  const double rays_per_s = f.seconds > 0 ? static_cast<double>(f.counters.rays) / f.seconds : 0;
  nlohmann::json js = {{"input", a.input},
                       {"engine", a.engine},
                       {"format", in.image.format().name()},
                       {"width", f.width},
                       {"height", f.height},
                       {"triangles", in.image.triangle_count()},
                       {"seconds", f.seconds},
                       {"rays_per_second", rays_per_s},
                       {"threads", a.threads},
                       {"counters", counters_json(f.counters)}};
  if (!a.quiet) {
    std::printf("%s: %ux%u, %s, engine %s: %.3f s, %.0f rays/s\n", a.input.c_str(), f.width,
                f.height, in.image.format().name().c_str(), a.engine.c_str(), f.seconds,
                rays_per_s);
    if (a.engine == "golden") {
      const Counters& c = f.counters;
      std::printf(
          "  packets %llu, traversal steps %llu, triangle tests %llu, leaves %llu, "
          "max stack %llu, failed packets %llu\n",
          static_cast<unsigned long long>(c.packets),
          static_cast<unsigned long long>(c.traversal_steps),
          static_cast<unsigned long long>(c.triangle_tests),
          static_cast<unsigned long long>(c.leaf_visits),
          static_cast<unsigned long long>(c.max_stack), static_cast<unsigned long long>(c.errors));
    }
  }
  if (!a.reference.empty()) {
    const Frame ref = run_any(a.reference, in, opt);
    const Agreement ag = compare_frames(f, ref);
    const double ref_rps =
        ref.seconds > 0 ? static_cast<double>(ref.counters.rays) / ref.seconds : 0;
    js["reference"] = {
        {"engine", a.reference},
        {"seconds", ref.seconds},
        {"rays_per_second", ref_rps},
        {"hit_agreement", ag.share()},
        {"pixels", ag.pixels},
        {"agree", ag.agree},
        {"only_this_hits", ag.only_a_hits},
        {"only_reference_hits", ag.only_b_hits},
        {"different_triangle", ag.different_tri},
        {"different_triangle_same_depth", ag.same_depth},
        {"psnr_db", std::isinf(ag.psnr_db) ? nlohmann::json("inf") : nlohmann::json(ag.psnr_db)}};
    if (!a.diff.empty()) write_image(a.diff, f.width, f.height, hit_difference_image(f, ref));
    if (!a.quiet)
      std::printf(
          "  against %s (%.0f rays/s): hit agreement %.4f%% (%llu of %llu pixels differ: "
          "%llu different triangle (%llu of them at the same depth), %llu only %s hits, %llu only "
          "%s hits), PSNR %.2f dB\n",
          a.reference.c_str(), ref_rps, 100.0 * ag.share(),
          static_cast<unsigned long long>(ag.pixels - ag.agree),
          static_cast<unsigned long long>(ag.pixels),
          static_cast<unsigned long long>(ag.different_tri),
          static_cast<unsigned long long>(ag.same_depth),
          static_cast<unsigned long long>(ag.only_a_hits), a.engine.c_str(),
          static_cast<unsigned long long>(ag.only_b_hits), a.reference.c_str(), ag.psnr_db);
  } else if (!a.diff.empty()) {
    throw Error("--diff needs --reference");
  }
  if (!a.stats.empty()) {
    std::ofstream out(a.stats);
    out << js.dump(2) << "\n";
    if (!out) throw Error(a.stats + ": cannot write the statistics");
  }
  return f.counters.errors ? 1 : 0;
}

}  // namespace

void add_render_commands(CLI::App& app, Action* action) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene, an OBJ file or a memory image");
  cmd->add_option("input", args->input, "scene.json, model.obj, builtin:NAME or scene.rcimg")
      ->required();
  cmd->add_option("--engine", args->engine, "golden (the bit-exact model) or embree")
      ->capture_default_str();
  cmd->add_option("--size", args->size, "frame size WxH (default: the scene's)");
  auto* cam =
      cmd->add_option("--camera", args->camera, "eye=X,Y,Z:look=X,Y,Z[:up=X,Y,Z][:fov=DEG]");
  cmd->add_flag("--auto-camera", args->auto_camera, "place the camera from the scene bounds")
      ->excludes(cam);
  cmd->add_option("-o,--output", args->output, "image to write (PNG, EXR, ...)")->required();
  cmd->add_option("--hits", args->hits, "hits file to write (docs/architecture.md)");
  cmd->add_option("--stats", args->stats, "statistics JSON to write");
  cmd->add_option("--reference", args->reference,
                  "also render with this engine and report hit agreement and PSNR");
  cmd->add_option("--diff", args->diff, "with --reference: write the hit difference image");
  cmd->add_option("--format", args->format, "number format for scene inputs: 7/16 or 8/23")
      ->capture_default_str();
  cmd->add_option("--models-path", args->models_path, "directories searched for meshes");
  cmd->add_option("--threads", args->threads, "threads (0: all)")->capture_default_str();
  cmd->add_flag("-q,--quiet", args->quiet, "no progress bar or summary");
  cmd->callback([args, action] { *action = [args] { return run_render(*args); }; });
}

}  // namespace rc::app
