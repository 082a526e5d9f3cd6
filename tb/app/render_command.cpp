// `raycore render`: render a scene with the golden model, the Embree reference or the verilated
// RTL core (--engine rtl, optionally checked bit for bit against the golden model with --check).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "board_sim.hpp"
#include "commands.hpp"
#include "compare.hpp"
#include "core_sim.hpp"
#include "embree_engine.hpp"
#include "error.hpp"
#include "geometry.hpp"
#include "image_file.hpp"
#include "job.hpp"
#include "output_paths.hpp"

namespace rc::app {
namespace {

using rc::scene::Error;

struct RenderArgs {
  std::string input, output, hits, stats, diff, size, camera, engine = "golden", reference;
  std::string format = "7/16", ray_source;  // ray_source "": host, raygen for the board
  std::string lighting = "headlight";
  uint32_t bounces = static_cast<uint32_t>(spec::kLightMaxBounces);
  bool bounces_given = false;
  std::vector<std::string> models_path;
  bool auto_camera = false, quiet = false;
  unsigned threads = 0;
  // --engine rtl
  bool check = false;
  uint32_t latency = 16;
  uint64_t stall_seed = 0;
  uint64_t watchdog = 200000;
  std::string threads_rtl = "default", isect_interval_rtl = "default", setup_units_rtl = "default";
  std::string secondary = "chip";  // --lighting scene: secondary rays on chip or host passes
  bool secondary_given = false;
  std::string trace, trace_window;
  std::vector<std::string> rtl_options_given;  // the --engine rtl options on the command line
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

// Whole numbers on the command line: decimal digits only. CLI11 alone would read "-1" into an
// unsigned option as 2^64 - 1 and "45deg" as 45.
const CLI::Validator kDigits(
    [](std::string& text) {
      if (text.empty() || text.size() > 19 ||
          text.find_first_not_of("0123456789") != std::string::npos)
        return "expected a whole number of decimal digits, got '" + text + "'";
      return std::string();
    },
    "UINT");

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
  return render_embree<T>(triangle_soup(*in.scene), opt, soup_lights(*in.scene));
}

Frame run_any(const std::string& engine, const RenderInput& in, const RenderOptions& opt) {
  if (in.image.format().is<fp24>()) return run_engine<fp24>(engine, in, opt);
  if (in.image.format().is<fp32ftz>()) return run_engine<fp32ftz>(engine, in, opt);
  throw Error(in.name + ": no engine for the number format " + in.image.format().name());
}

// ---- --engine rtl ----

std::string hex_bits(uint32_t bits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%06x", bits);
  return buf;
}

std::string describe_hit(const HitRecord& h) {
  if (h.tri < 0 && h.t == 0 && h.u == 0 && h.v == 0) return "miss";
  char buf[256];
  std::snprintf(buf, sizeof buf, "tri %d, t %.9g (%s), u %.9g (%s), v %.9g (%s)", h.tri,
                fp24::from_bits(h.t).to_double(), hex_bits(h.t).c_str(),
                fp24::from_bits(h.u).to_double(), hex_bits(h.u).c_str(),
                fp24::from_bits(h.v).to_double(), hex_bits(h.v).c_str());
  return buf;
}

std::string describe_rgb(const Frame& f, size_t pix) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "rgb (%u, %u, %u)", f.rgb[3 * pix], f.rgb[3 * pix + 1],
                f.rgb[3 * pix + 2]);
  return buf;
}

void parse_window(const std::string& text, uint64_t& first, uint64_t& last) {
  unsigned long long a = 0, b = 0;
  char colon = 0, extra = 0;
  std::istringstream ss(text);
  if (!(ss >> a >> colon >> b) || colon != ':' || (ss >> extra) || b < a)
    throw Error("--trace-window: expected FIRST:LAST cycles with FIRST <= LAST, got '" + text +
                "'");
  first = a;
  last = b;
}

double share(uint64_t part, uint64_t whole) {
  return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

// The verilated core model that --threads-rtl, --isect-interval-rtl and --setup-units-rtl name
// (one of them at a time: each model differs from the default in one parameter).
harness::CoreModel rtl_model(const RenderArgs& a) {
  if (a.threads_rtl != "1" && a.threads_rtl != "16" && a.threads_rtl != "64" &&
      a.threads_rtl != "default")
    throw Error("--threads-rtl: expected 1, 16, 64 or default, got '" + a.threads_rtl + "'");
  if (a.isect_interval_rtl != "1" && a.isect_interval_rtl != "default")
    throw Error("--isect-interval-rtl: expected 1 or default, got '" + a.isect_interval_rtl + "'");
  if (a.setup_units_rtl != "1" && a.setup_units_rtl != "2" && a.setup_units_rtl != "default")
    throw Error("--setup-units-rtl: expected 1, 2 or default, got '" + a.setup_units_rtl + "'");
  const std::pair<const char*, const std::string*> set[] = {
      {"--threads-rtl", &a.threads_rtl},
      {"--isect-interval-rtl", &a.isect_interval_rtl},
      {"--setup-units-rtl", &a.setup_units_rtl}};
  std::string given;
  for (const auto& [name, value] : set) {
    if (*value == "default") continue;
    if (!given.empty())
      throw Error(given + " and " + name + " " + *value +
                  ": no core model has both (one of them at a time)");
    given = std::string(name) + " " + *value;
  }
  if (a.threads_rtl == "1") return harness::CoreModel::kThreads1;
  if (a.threads_rtl == "16") return harness::CoreModel::kThreads16;
  if (a.threads_rtl == "64") return harness::CoreModel::kThreads64;
  if (a.isect_interval_rtl == "1") return harness::CoreModel::kIsect1;
  if (a.setup_units_rtl == "1") return harness::CoreModel::kSetup1;
  if (a.setup_units_rtl == "2") return harness::CoreModel::kSetup2;
  return harness::CoreModel::kDefault;
}

// --secondary: where --engine rtl makes a lit frame's secondary rays.
harness::SecondaryPath parse_secondary(const std::string& text) {
  if (text == "chip") return harness::SecondaryPath::kOnChip;
  if (text == "host") return harness::SecondaryPath::kHost;
  throw Error("--secondary: expected chip or host, got '" + text + "'");
}

// The RTL run's figures: for --stats and for the summary on stdout.
nlohmann::json rtl_json(const harness::CoreSimResult& r, const RenderArgs& a) {
  const auto perf = [&r](int64_t k) { return r.perf[static_cast<size_t>(k)]; };
  const Counters& c = r.frame.counters;
  const double eff =
      share(harness::ideal_cycles(c, harness::isect_interval(rtl_model(a))), r.cycles);
  nlohmann::json busy = {{"setup", share(perf(spec::kCorePerfSetupBusy), r.cycles)},
                         {"trav", share(perf(spec::kCorePerfTravBusy), r.cycles)},
                         {"list", share(perf(spec::kCorePerfListBusy), r.cycles)},
                         {"isect", share(perf(spec::kCorePerfIsectBusy), r.cycles)},
                         {"shade", share(perf(spec::kCorePerfShadeBusy), r.cycles)},
                         {"core", share(perf(spec::kCorePerfBusyCycles), r.cycles)}};
  const harness::UnitUtilisation u =
      harness::unit_utilisation(r.perf, r.cycles, harness::isect_interval(rtl_model(a)),
                                harness::model_setup_units(rtl_model(a)));
  nlohmann::json util = {{"setup", u.setup},
                         {"trav", u.trav},
                         {"list", u.list},
                         {"isect", u.isect},
                         {"shade", u.shade}};
  nlohmann::json mem = nlohmann::json::object();
  for (int i = 0; i < harness::kCorePorts; ++i) {
    const harness::MemoryStats& m = r.memory[static_cast<size_t>(i)];
    mem[harness::core_port_name(i)] = {{"requests", m.requests},
                                       {"bytes", m.bytes},
                                       {"bytes_per_cycle", share(m.bytes, r.cycles)},
                                       {"max_outstanding", m.max_outstanding},
                                       {"error_responses", m.errors}};
  }
  nlohmann::json perf_all = nlohmann::json::array();
  for (uint64_t v : r.perf) perf_all.push_back(v);
  // Scene lighting: the secondary passes of one kind, summed (null without lighting).
  const auto passes_json = [&](const harness::SecondaryPasses& p,
                               const Counters& sc) -> nlohmann::json {
    if (!r.lit) return nullptr;
    const harness::UnitUtilisation su =
        harness::unit_utilisation(p.perf, p.cycles, harness::isect_interval(rtl_model(a)),
                                  harness::model_setup_units(rtl_model(a)));
    nlohmann::json pass_perf = nlohmann::json::array();
    for (uint64_t v : p.perf) pass_perf.push_back(v);
    return {{"passes", p.passes},
            {"packets", p.packets},
            {"cycles", p.cycles},
            {"rays", sc.rays},
            {"rays_per_cycle", share(sc.rays, p.cycles)},
            {"traversal_steps", sc.traversal_steps},
            {"triangle_tests", sc.triangle_tests},
            {"efficiency",
             share(harness::ideal_cycles(sc, harness::isect_interval(rtl_model(a))), p.cycles)},
            {"utilisation",
             {{"setup", su.setup},
              {"trav", su.trav},
              {"list", su.list},
              {"isect", su.isect},
              {"shade", su.shade}}},
            {"busiest_unit", {{"unit", su.busiest_name}, {"utilisation", su.busiest}}},
            {"error_bits", p.error_bits},
            {"perf", pass_perf}};
  };
  // The core's own counters per ray kind, over every run of the frame (the primary run and the
  // secondary passes).
  std::array<harness::KindCounters, harness::kRayKinds> kc{};
  for (const auto* p : {&r.perf, &r.shadow.perf, &r.bounce.perf, &r.refract.perf}) {
    const auto k = harness::kind_counters(*p);
    for (size_t i = 0; i < kc.size(); ++i) {
      kc[i].rays += k[i].rays;
      kc[i].traversal_steps += k[i].traversal_steps;
      kc[i].triangle_tests += k[i].triangle_tests;
    }
  }
  // Each kind's share of the frame's cycles (every run's) in the traversal sub-units and the
  // intersection unit: its work over what the units could have done in those cycles.
  const uint64_t frame_cycles = r.cycles + r.shadow.cycles + r.bounce.cycles + r.refract.cycles;
  const uint32_t interval = harness::isect_interval(rtl_model(a));
  nlohmann::json kinds = nlohmann::json::object();
  for (size_t i = 0; i < kc.size(); ++i) {
    Counters kind_work;
    kind_work.traversal_steps = kc[i].traversal_steps;
    kind_work.triangle_tests = kc[i].triangle_tests;
    kinds[harness::ray_kind_name(static_cast<int>(i))] = {
        {"rays", kc[i].rays},
        {"traversal_steps", kc[i].traversal_steps},
        {"triangle_tests", kc[i].triangle_tests},
        {"rays_per_cycle", share(kc[i].rays, frame_cycles)},
        {"trav_utilisation", share(kc[i].traversal_steps, 4 * frame_cycles)},
        {"isect_utilisation", share(kc[i].triangle_tests * interval, frame_cycles)},
        {"efficiency", share(harness::ideal_cycles(kind_work, interval), frame_cycles)}};
  }
  return {{"cycles", r.cycles},
          {"secondary", !r.lit            ? "none"
                        : r.on_chip_kinds ? "chip"
                                          : "host"},
          {"frame_cycles", frame_cycles},
          {"core_cycles_counter", perf(spec::kCorePerfCycles)},
          {"rays", c.rays},
          {"rays_per_cycle", share(c.rays, r.cycles)},
          {"busy_share", busy},
          {"utilisation", util},
          {"busiest_unit", {{"unit", u.busiest_name}, {"utilisation", u.busiest}}},
          {"traversal_steps", c.traversal_steps},
          {"triangle_tests", c.triangle_tests},
          {"efficiency", eff},
          {"memory", mem},
          {"simulated_cycles_per_second", r.cycles_per_second},
          {"wall_seconds", r.seconds},
          {"error_bits", r.error_bits},
          {"threads", harness::model_threads(rtl_model(a))},
          {"isect_interval", harness::isect_interval(rtl_model(a))},
          {"setup_units", harness::model_setup_units(rtl_model(a))},
          {"latency", a.latency},
          {"stall_seed", a.stall_seed},
          {"perf", perf_all},
          {"kinds", kinds},
          {"shadow_pass", passes_json(r.shadow, r.frame.shadow_counters)},
          {"bounce_pass", passes_json(r.bounce, r.frame.bounce_counters)},
          {"refract_pass", passes_json(r.refract, r.frame.refract_counters)}};
}

void print_rtl_summary(const nlohmann::json& j) {
  const auto& b = j["busy_share"];
  std::printf("  rtl: %llu cycles, %llu rays, %.4f rays/cycle, efficiency %.3f\n",
              j["cycles"].get<unsigned long long>(), j["rays"].get<unsigned long long>(),
              j["rays_per_cycle"].get<double>(), j["efficiency"].get<double>());
  const auto& u = j["utilisation"];
  std::printf(
      "  utilisation: setup %.3f, trav %.3f, list %.3f, isect %.3f, shade %.3f; busiest: %s "
      "%.3f\n",
      u["setup"].get<double>(), u["trav"].get<double>(), u["list"].get<double>(),
      u["isect"].get<double>(), u["shade"].get<double>(),
      j["busiest_unit"]["unit"].get<std::string>().c_str(),
      j["busiest_unit"]["utilisation"].get<double>());
  std::printf("  operations per cycle: setup %.3f, trav %.3f, list %.3f, isect %.3f, shade %.3f\n",
              b["setup"].get<double>(), b["trav"].get<double>(), b["list"].get<double>(),
              b["isect"].get<double>(), b["shade"].get<double>());
  std::printf("  traversal steps %llu, triangle tests %llu\n",
              j["traversal_steps"].get<unsigned long long>(),
              j["triangle_tests"].get<unsigned long long>());
  std::printf("  memory:");
  for (int i = 0; i < harness::kCorePorts; ++i) {
    const auto& m = j["memory"][harness::core_port_name(i)];
    std::printf("%s %s %llu req %llu B", i ? "," : "", harness::core_port_name(i),
                m["requests"].get<unsigned long long>(), m["bytes"].get<unsigned long long>());
  }
  std::printf("\n  simulation: %.0f cycles/s, %.2f s wall\n",
              j["simulated_cycles_per_second"].get<double>(), j["wall_seconds"].get<double>());
  // The core's own counters per kind, once secondary rays were traced.
  const auto& jk = j["kinds"];
  if (j["secondary"] == "chip")
    std::printf(
        "  secondary rays made on chip (rc_tracer): the figures above are the whole lit "
        "frame's, every kind's packets in the core together\n");
  if (jk["shadow"]["rays"].get<uint64_t>() + jk["bounce"]["rays"].get<uint64_t>() +
          jk["refract"]["rays"].get<uint64_t>() >
      0) {
    std::printf(
        "  the core's counters per ray kind over the frame's %llu cycles (rays, traversal "
        "steps, triangle tests; rays/cycle; share of the traversal and intersection capacity; "
        "efficiency):\n",
        j["frame_cycles"].get<unsigned long long>());
    for (int i = 0; i < harness::kRayKinds; ++i) {
      const std::string name = harness::ray_kind_name(i);
      const auto& k = jk[name];
      std::printf("    %-8s %llu, %llu, %llu; %.4f rays/cycle; trav %.3f, isect %.3f; eff %.3f\n",
                  name.c_str(), k["rays"].get<unsigned long long>(),
                  k["traversal_steps"].get<unsigned long long>(),
                  k["triangle_tests"].get<unsigned long long>(), k["rays_per_cycle"].get<double>(),
                  k["trav_utilisation"].get<double>(), k["isect_utilisation"].get<double>(),
                  k["efficiency"].get<double>());
    }
  }
  const std::pair<const char*, const char*> kinds[] = {
      {"shadow", "shadow"}, {"bounce", "mirror"}, {"refract", "refraction"}};
  for (const auto& [key, kind] : kinds) {
    const auto& s = j[std::string(key) + "_pass"];
    if (s.is_null() || s["passes"].get<uint64_t>() == 0) continue;
    std::printf(
        "  rtl %s passes (%llu; packets from the core's hits, light terms on the host): %llu "
        "packets, %llu rays, %llu cycles, %.4f rays/cycle, efficiency %.3f, busiest: %s %.3f\n",
        kind, s["passes"].get<unsigned long long>(), s["packets"].get<unsigned long long>(),
        s["rays"].get<unsigned long long>(), s["cycles"].get<unsigned long long>(),
        s["rays_per_cycle"].get<double>(), s["efficiency"].get<double>(),
        s["busiest_unit"]["unit"].get<std::string>().c_str(),
        s["busiest_unit"]["utilisation"].get<double>());
  }
}

harness::CoreSimResult run_rtl(const RenderArgs& a, const RenderInput& in,
                               const RenderOptions& opt) {
  if (!in.image.format().is<fp24>())
    throw Error("--engine rtl: the RTL core is built for fp24 (--format 7/16); " + in.name +
                " holds " + in.image.format().name() + " values");
  harness::CoreSimOptions so;
  for (auto& m : so.memory) m.latency = a.latency;
  so.stall_seed = a.stall_seed;
  so.watchdog_cycles = a.watchdog;
  so.trace_path = a.trace;
  if (!a.trace_window.empty()) parse_window(a.trace_window, so.trace_first, so.trace_last);
  so.progress = !a.quiet;
  so.secondary = parse_secondary(a.secondary);
  return harness::render_rtl(in.image, opt, so, rtl_model(a));
}

// Where --check writes its difference image on a mismatch: --diff, or beside the output
// (out/x.png -> out/x.diff.png).
std::string check_diff_path(const RenderArgs& a) {
  if (!a.diff.empty()) return a.diff;
  return std::filesystem::path(a.output).replace_extension(".diff.png").string();
}

// --check: the golden model's frame against the RTL's, bit for bit. Returns whether they agree.
bool check_rtl(const RenderArgs& a, const RenderInput& in, const RenderOptions& opt,
               const Frame& rtl, const harness::CoreSimResult* sim,
               const harness::BoardSimResult* board, nlohmann::json& js) {
  RenderOptions gopt = opt;
  gopt.progress = false;
  const Frame gold = render_golden(load_geometry<fp24>(in.image), gopt);
  const ExactComparison cmp = compare_exact(gold, rtl);
  std::vector<std::string> counters, allowed;  // differences that fail the check, and not
  // The board's run has no CoreSimResult: its frame, and lit, its counters over every kind with
  // the per-kind ones (the secondary kinds made on chip, as rc_tracer's run).
  harness::CoreSimResult board_frame;
  if (!sim) {
    board_frame.frame = rtl;
    if (board) {
      board_frame.perf = board->perf;
      if (board->lit) board_frame.on_chip_kinds = harness::kTracerKinds;
    }
  }
  for (const CounterDifference& d :
       harness::frame_counter_differences(gold, sim ? *sim : board_frame))
    (d.required ? counters : allowed).push_back(d.text());
  // Scene lighting: which lights reach each pixel, what its first mirror and refraction rays hit
  // (the secondary rays' counters are frame_counter_differences()' above).
  const auto differ = [](const auto& x, const auto& y) -> uint64_t {
    if (x.size() != y.size()) return std::max(x.size(), y.size());
    uint64_t n = 0;
    for (size_t i = 0; i < x.size(); ++i) n += x[i] != y[i] ? 1 : 0;
    return n;
  };
  const uint64_t light_differ = differ(gold.light_mask, rtl.light_mask);
  const uint64_t bounce_differ = differ(gold.bounce_tri, rtl.bounce_tri);
  const uint64_t refract_differ = differ(gold.refract_tri, rtl.refract_tri);
  // The run itself: idle at the end, misses without a hit record, one write per pixel, no
  // watchdog (the regression tests judge a run by the same function).
  const std::vector<std::string> run =
      sim ? harness::run_problems(*sim) : std::vector<std::string>{};
  const bool ok = cmp.equal() && light_differ == 0 && bounce_differ == 0 && refract_differ == 0 &&
                  counters.empty() && run.empty();
  js["check"] = {{"engine", "golden"},
                 {"pixels", cmp.pixels},
                 {"differing_pixels", cmp.differing},
                 {"rgb_differ", cmp.rgb_differ},
                 {"hits_differ", cmp.hits_differ},
                 {"light_masks_differ", light_differ},
                 {"bounce_hits_differ", bounce_differ},
                 {"refract_hits_differ", refract_differ},
                 {"counter_differences", counters},
                 {"counter_differences_after_error", allowed},
                 {"run_problems", run},
                 {"pass", ok}};
  if (ok) {
    if (!a.quiet) {
      std::printf("  check against golden: %llu pixels bit for bit equal, counters %s\n",
                  static_cast<unsigned long long>(cmp.pixels),
                  allowed.empty() ? "equal" : "equal but for the failed packets' work:");
      for (const std::string& d : allowed) std::printf("    %s\n", d.c_str());
    }
    return true;
  }
  std::printf("  check against golden: MISMATCH\n");
  if (!cmp.equal()) {
    const auto pix = static_cast<size_t>(cmp.first);
    const uint32_t x = static_cast<uint32_t>(pix % rtl.width),
                   y = static_cast<uint32_t>(pix / rtl.width);
    std::printf(
        "  %llu of %llu pixels differ (%llu in rgb, %llu in the hit record); the first: pixel "
        "(%u, %u), packet (%u, %u) ray %u\n",
        static_cast<unsigned long long>(cmp.differing), static_cast<unsigned long long>(cmp.pixels),
        static_cast<unsigned long long>(cmp.rgb_differ),
        static_cast<unsigned long long>(cmp.hits_differ), x, y, x / 2, y / 2,
        (x & 1u) | (y & 1u) << 1);
    std::printf("    golden: %s, %s\n", describe_hit(gold.hits[pix]).c_str(),
                describe_rgb(gold, pix).c_str());
    std::printf("    rtl:    %s, %s\n", describe_hit(rtl.hits[pix]).c_str(),
                describe_rgb(rtl, pix).c_str());
    // Where to look in a waveform: from the cycle the packet was taken to its pixel's write.
    const size_t packet = static_cast<size_t>(y / 2) * ((rtl.width + 1) / 2) + x / 2;
    if (sim && packet < sim->packet_cycle.size() && pix < sim->pixel_cycle.size()) {
      const unsigned long long from = sim->packet_cycle[packet], to = sim->pixel_cycle[pix];
      std::printf(
          "    the core took the packet at cycle %llu and wrote the pixel at cycle %llu: add "
          "--trace f.fst --trace-window %llu:%llu (docs/debugging.md)\n",
          from, to, from > 20 ? from - 20 : 0ull, to + 20);
    }
    js["check"]["first"] = {{"x", x}, {"y", y}};
    // --diff, or next to the output: out/x.png -> out/x.diff.png
    const std::string diff = check_diff_path(a);
    write_image(diff, rtl.width, rtl.height, exact_difference_image(gold, rtl));
    std::printf("    difference image (red: hit record, yellow: rgb only): %s\n", diff.c_str());
  }
  if (light_differ)
    std::printf("  %llu pixels differ in the lights that reach them\n",
                static_cast<unsigned long long>(light_differ));
  if (bounce_differ)
    std::printf("  %llu pixels differ in what their first mirror ray hits\n",
                static_cast<unsigned long long>(bounce_differ));
  if (refract_differ)
    std::printf("  %llu pixels differ in what their first refraction ray hits\n",
                static_cast<unsigned long long>(refract_differ));
  for (const std::string& d : run) std::printf("  run: %s\n", d.c_str());
  for (const std::string& d : counters) std::printf("  counter %s\n", d.c_str());
  for (const std::string& d : allowed)
    std::printf("  counter %s (after an error: allowed to differ)\n", d.c_str());
  return false;
}

// --engine board: the verilated board (rtl/board/rc_board.sv) with its on-chip ray generation.
harness::BoardSimResult run_board(const RenderArgs& a, const RenderInput& in,
                                  const RenderOptions& opt) {
  if (!in.image.format().is<fp24>())
    throw Error("--engine board: the board is built for fp24 (--format 7/16); " + in.name +
                " holds " + in.image.format().name() + " values");
  harness::BoardSimOptions bo;
  bo.watchdog_cycles = a.watchdog * 10;
  bo.progress = !a.quiet;
  return harness::render_board(in.image, opt, bo);
}

nlohmann::json board_json(const harness::BoardSimResult& r) {
  const Counters& c = r.frame.counters;
  const double eff = share(harness::ideal_cycles(c), r.cycles);
  nlohmann::json perf_all = nlohmann::json::array();
  for (uint64_t v : r.perf) perf_all.push_back(v);
  return {{"cycles", r.cycles},
          {"rays", c.rays},
          {"rays_per_cycle", share(c.rays, r.cycles)},
          {"efficiency", eff},
          {"status", r.status},
          {"error_bits", r.error_bits},
          {"framebuffer_readback_differ", r.fb_readback_differ},
          {"register_readback_differ", r.register_readback_differ},
          {"simulated_cycles_per_second", r.cycles_per_second},
          {"wall_seconds", r.seconds},
          {"perf", perf_all}};
}

int run_render(const RenderArgs& a) {
  if (a.engine != "golden" && a.engine != "embree" && a.engine != "rtl" && a.engine != "board")
    throw Error("--engine: expected golden, embree, rtl or board, got '" + a.engine + "'");
  if (a.check && a.engine != "rtl" && a.engine != "board")
    throw Error("--check needs --engine rtl or board");
  if (a.engine == "board" && !a.ray_source.empty() && a.ray_source != "raygen")
    throw Error(
        "--engine board generates its rays on chip: --ray-source raygen (the default "
        "with the board), not '" +
        a.ray_source + "'");
  const Lighting lighting = parse_lighting(a.lighting);
  if (a.bounces > static_cast<uint32_t>(spec::kLightBounceLimit))
    throw Error("--bounces: at most " + std::to_string(spec::kLightBounceLimit) + ", got " +
                std::to_string(a.bounces));
  if (a.bounces_given && lighting != Lighting::kScene)
    throw Error(
        "--bounces needs --lighting scene (the headlight traces no mirror or refraction rays)");
  if (!a.reference.empty() && a.reference != "embree" && a.reference != "golden")
    throw Error("--reference: expected embree or golden, got '" + a.reference + "'");
  if (!a.diff.empty() && a.reference.empty() && !a.check)
    throw Error("--diff needs --reference (or --engine rtl --check)");
  if (a.engine != "rtl" && !a.rtl_options_given.empty())
    throw Error(a.rtl_options_given.front() + " needs --engine rtl");
  if (!a.trace_window.empty() && a.trace.empty()) throw Error("--trace-window needs --trace");
  if (a.engine == "rtl") (void)rtl_model(a);  // the model options (--threads-rtl, ...)
  if (a.engine == "rtl") (void)parse_secondary(a.secondary);
  if (a.secondary_given && lighting != Lighting::kScene)
    throw Error("--secondary needs --lighting scene (the headlight traces no secondary rays)");
  uint64_t window_first = 0, window_last = 0;  // checked here, used by run_rtl()
  if (!a.trace_window.empty()) parse_window(a.trace_window, window_first, window_last);
  const RaySource ray_source = a.ray_source.empty()
                                   ? (a.engine == "board" ? RaySource::kRayGen : RaySource::kHost)
                                   : parse_ray_source(a.ray_source);
  uint32_t width = 0, height = 0;
  if (!a.size.empty()) parse_size(a.size, width, height);
  std::optional<Camera> camera;
  if (!a.camera.empty()) camera = parse_camera(a.camera);
  const scene::NumberFormat format = scene::NumberFormat::parse(a.format);

  // The outputs before any work: each writable, none an input, no two the same file.
  const std::string diff = a.check ? check_diff_path(a) : a.diff;
  const std::vector<NamedPath> outputs = {{"-o", a.output},
                                          {"--hits", a.hits},
                                          {"--stats", a.stats},
                                          {"--trace", a.trace},
                                          {"--diff", diff}};
  check_outputs({{"input", a.input}}, outputs);
  check_image_name(a.output);
  if (!diff.empty()) check_image_name(diff);

  scene::LoadOptions load;
  load.models_path = a.models_path;
  const RenderInput in = load_render_input(a.input, load, format);
  require_valid(in.image);
  if (in.scene) check_outputs(scene_inputs(*in.scene), outputs);  // meshes and MTL files too
  RenderOptions opt = input_options(in);
  if (width) {
    opt.width = width;
    opt.height = height;
  }
  if (camera) opt.camera = *camera;
  if (a.auto_camera) opt.camera = auto_camera_for(in.image);
  opt.threads = a.threads;
  opt.progress = !a.quiet;
  opt.ray_source = ray_source;
  opt.lighting = lighting;
  opt.max_bounces = a.bounces;

  // Secondary rays on chip: a model and an image the tree controller can take, before any work.
  if (a.engine == "rtl" && parse_secondary(a.secondary) == harness::SecondaryPath::kOnChip)
    if (const std::string why = harness::on_chip_problem(in.image, opt, rtl_model(a)); !why.empty())
      throw Error(why);

  std::optional<harness::CoreSimResult> rtl;
  std::optional<harness::BoardSimResult> board;
  if (a.engine == "rtl") rtl = run_rtl(a, in, opt);
  if (a.engine == "board") board = run_board(a, in, opt);
  const Frame f = rtl ? rtl->frame : board ? board->frame : run_any(a.engine, in, opt);
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
                       {"ray_source", ray_source_name(opt.ray_source)},
                       {"lighting", lighting_name(opt.lighting)},
                       {"counters", counters_json(f.counters)}};
  if (!f.light_mask.empty()) js["max_bounces"] = opt.max_bounces;
  // Secondary rays on chip: the frame's counters are the core's over every kind (rtl.kinds
  // splits rays, traversal steps and triangle tests by kind).
  const bool on_chip = (rtl && rtl->on_chip_kinds != 0) || (board && board->lit);
  if (on_chip) js["counters_kinds"] = "all";
  if (!f.light_mask.empty() && a.engine != "embree" && !on_chip) {
    js["shadow_counters"] = counters_json(f.shadow_counters);
    js["bounce_counters"] = counters_json(f.bounce_counters);
    js["refract_counters"] = counters_json(f.refract_counters);
  }
  if (!a.quiet) {
    std::printf("%s: %ux%u, %s, engine %s: %.3f s, %.0f rays/s\n", a.input.c_str(), f.width,
                f.height, in.image.format().name().c_str(), a.engine.c_str(), f.seconds,
                rays_per_s);
    if (a.engine != "embree") {
      const Counters& c = f.counters;
      std::printf(
          "  %spackets %llu, traversal steps %llu, triangle tests %llu, leaves %llu, "
          "max stack %llu, failed packets %llu\n",
          on_chip ? "every kind: " : "", static_cast<unsigned long long>(c.packets),
          static_cast<unsigned long long>(c.traversal_steps),
          static_cast<unsigned long long>(c.triangle_tests),
          static_cast<unsigned long long>(c.leaf_visits),
          static_cast<unsigned long long>(c.max_stack), static_cast<unsigned long long>(c.errors));
      if (!f.light_mask.empty() && !on_chip) {
        const Counters& sc = f.shadow_counters;
        std::printf(
            "  shadow rays %llu in %llu packets, traversal steps %llu, triangle tests %llu, "
            "failed packets %llu\n",
            static_cast<unsigned long long>(sc.rays), static_cast<unsigned long long>(sc.packets),
            static_cast<unsigned long long>(sc.traversal_steps),
            static_cast<unsigned long long>(sc.triangle_tests),
            static_cast<unsigned long long>(sc.errors));
        const Counters& bc = f.bounce_counters;
        std::printf(
            "  mirror rays %llu in %llu packets (--bounces %u), traversal steps %llu, triangle "
            "tests %llu, failed packets %llu\n",
            static_cast<unsigned long long>(bc.rays), static_cast<unsigned long long>(bc.packets),
            opt.max_bounces, static_cast<unsigned long long>(bc.traversal_steps),
            static_cast<unsigned long long>(bc.triangle_tests),
            static_cast<unsigned long long>(bc.errors));
        const Counters& tc = f.refract_counters;
        std::printf(
            "  refraction rays %llu in %llu packets, traversal steps %llu, triangle tests %llu, "
            "failed packets %llu\n",
            static_cast<unsigned long long>(tc.rays), static_cast<unsigned long long>(tc.packets),
            static_cast<unsigned long long>(tc.traversal_steps),
            static_cast<unsigned long long>(tc.triangle_tests),
            static_cast<unsigned long long>(tc.errors));
      }
    }
  }
  bool check_ok = true;
  if (rtl) {
    js["rtl"] = rtl_json(*rtl, a);
    if (!a.quiet) print_rtl_summary(js["rtl"]);
    if (a.check) check_ok = check_rtl(a, in, opt, f, &*rtl, nullptr, js);
  }
  if (board) {
    js["board"] = board_json(*board);
    const auto& b = js["board"];
    if (!a.quiet)
      std::printf(
          "  board: %llu cycles, %.4f rays/cycle, efficiency %.3f, status 0x%x; read back "
          "through the ports: %llu framebuffer pixels and %llu registers differ; %.0f "
          "simulated cycles/s\n",
          b["cycles"].get<unsigned long long>(), b["rays_per_cycle"].get<double>(),
          b["efficiency"].get<double>(), b["status"].get<unsigned>(),
          b["framebuffer_readback_differ"].get<unsigned long long>(),
          b["register_readback_differ"].get<unsigned long long>(),
          b["simulated_cycles_per_second"].get<double>());
    if (board->fb_readback_differ || board->register_readback_differ) {
      std::printf("  board: MISMATCH between the monitored writes and the ports' read-back\n");
      check_ok = false;
    }
    // The board's ray generator makes the primary rays; the lit board's tracer the others.
    const uint64_t primary = static_cast<uint64_t>(f.width) * f.height;
    for (const std::string& p :
         harness::kind_problems(board->perf, {board->lit ? primary : f.counters.rays, 0, 0, 0},
                                board->lit ? harness::kTracerKinds : 0u)) {
      std::printf("  board: per-kind counters: %s\n", p.c_str());
      check_ok = false;
    }
    if (a.check && !check_rtl(a, in, opt, f, nullptr, &*board, js)) check_ok = false;
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
    if (!f.light_mask.empty() && !ref.light_mask.empty()) {
      const LightAgreement la = compare_lights(f, ref, in.image.light_count());
      js["reference"]["light_agreement"] = la.share();
      js["reference"]["light_tests"] = la.tests;
      js["reference"]["only_this_lit"] = la.only_a_lit;
      js["reference"]["only_reference_lit"] = la.only_b_lit;
      if (!a.quiet)
        std::printf(
            "  shadow test against %s: %.4f%% of %llu (pixel, light) pairs agree (%llu lit only "
            "by %s, %llu only by %s)\n",
            a.reference.c_str(), 100.0 * la.share(), static_cast<unsigned long long>(la.tests),
            static_cast<unsigned long long>(la.only_a_lit), a.engine.c_str(),
            static_cast<unsigned long long>(la.only_b_lit), a.reference.c_str());
      // The first mirror and refraction rays' hits.
      const auto child_agreement = [&](const char* key, const char* what,
                                       const BounceAgreement& ba) {
        js["reference"][std::string(key) + "_agreement"] = ba.share();
        js["reference"][std::string(key) + "_rays"] = ba.rays;
        js["reference"][std::string(key) + "_only_one"] = ba.only_one;
        if (!a.quiet && ba.rays > 0)
          std::printf(
              "  first %s ray against %s: %.4f%% of %llu agree on the triangle hit (%llu traced "
              "by one engine only)\n",
              what, a.reference.c_str(), 100.0 * ba.share(),
              static_cast<unsigned long long>(ba.rays),
              static_cast<unsigned long long>(ba.only_one));
      };
      child_agreement("bounce", "mirror", compare_bounces(f, ref));
      child_agreement("refract", "refraction", compare_refractions(f, ref));
    }
  }
  if (!a.stats.empty()) {
    std::ofstream out(a.stats);
    out << js.dump(2) << "\n";
    if (!out) throw Error(a.stats + ": cannot write the statistics");
  }
  if (!check_ok) return 1;
  return f.counters.errors ? 1 : 0;
}

struct BoardImageArgs {
  std::string input, output, size, camera, format = "7/16", lighting = "headlight";
  std::vector<std::string> models_path;
  bool auto_camera = false;
  uint32_t fb_pixels = static_cast<uint32_t>(spec::kBoardFbPixels);
  uint32_t bounces = static_cast<uint32_t>(spec::kLightMaxBounces);
};

// `raycore board-image`: the block RAM contents and register file of the board build.
int run_board_image(const BoardImageArgs& a) {
  uint32_t width = 0, height = 0;
  if (!a.size.empty()) parse_size(a.size, width, height);
  std::optional<Camera> camera;
  if (!a.camera.empty()) camera = parse_camera(a.camera);
  const scene::NumberFormat format = scene::NumberFormat::parse(a.format);
  check_output_dir({"-o", a.output});
  for (const std::string& name : harness::board_image_files()) {
    const std::string file = (std::filesystem::path(a.output) / name).string();
    if (same_file(file, a.input))
      throw Error("-o " + a.output + ": would overwrite the input " + a.input + " (" + name + ")");
  }
  scene::LoadOptions load;
  load.models_path = a.models_path;
  const RenderInput in = load_render_input(a.input, load, format);
  require_valid(in.image);
  RenderOptions opt = input_options(in);
  if (width) {
    opt.width = width;
    opt.height = height;
  }
  if (camera) opt.camera = *camera;
  if (a.auto_camera) opt.camera = auto_camera_for(in.image);
  opt.lighting = parse_lighting(a.lighting);
  opt.max_bounces = a.bounces;
  const harness::BoardImage b = harness::make_board_image(in.image, opt, a.fb_pixels);
  harness::write_board_image(b, a.output, a.input);
  std::printf("%s: %s board image for a %ux%u frame in %s:", a.input.c_str(),
              b.lit ? "lit" : "headlight", b.width, b.height, a.output.c_str());
  for (const auto& rom : b.roms)
    std::printf(" %s %zu x %u bits,", rom.name.c_str(), rom.records.size(), rom.width);
  for (const auto& rom : b.light_roms)
    std::printf(" %s %zu x %u bits,", rom.name.c_str(), rom.records.size(), rom.width);
  std::printf(" regs %zu\n", b.regs.size());
  return 0;
}

}  // namespace

void add_render_commands(CLI::App& app, Action* action) {
  {
    auto args = std::make_shared<BoardImageArgs>();
    CLI::App* cmd = app.add_subcommand(
        "board-image",
        "Write the board build's ROM and register contents (hex files and board.json) for a "
        "scene and frame (docs/fpga.md)");
    cmd->add_option("input", args->input, "scene.json, model.obj, builtin:NAME or scene.rcimg")
        ->required();
    cmd->add_option("-o,--output", args->output, "directory to write")->required();
    cmd->add_option("--size", args->size, "frame size WxH (default: the scene's)");
    auto* cam =
        cmd->add_option("--camera", args->camera, "eye=X,Y,Z:look=X,Y,Z[:up=X,Y,Z][:fov=DEG]");
    cmd->add_flag("--auto-camera", args->auto_camera, "place the camera from the scene bounds")
        ->excludes(cam);
    cmd->add_option("--format", args->format, "number format (the board is fp24: 7/16)")
        ->capture_default_str();
    cmd->add_option("--models-path", args->models_path, "directories searched for meshes");
    cmd->add_option("--fb-pixels", args->fb_pixels,
                    "the board's framebuffer size in pixels (1 to 16777216)")
        ->capture_default_str()
        ->check(kDigits & CLI::Range(1u, 1u << 24));
    cmd->add_option("--lighting", args->lighting,
                    "headlight (the board with the core alone) or scene (the lit board: the "
                    "scene's lights, shadow, mirror and refraction rays; a scene without lights "
                    "keeps the headlight)")
        ->capture_default_str();
    cmd->add_option("--bounces", args->bounces,
                    "with --lighting scene: the depth of each pixel's tree of mirror and "
                    "refraction rays")
        ->capture_default_str()
        ->check(kDigits & CLI::Range(0u, static_cast<unsigned>(spec::kLightBounceLimit)));
    cmd->callback([args, action] { *action = [args] { return run_board_image(*args); }; });
  }

  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene, an OBJ file or a memory image");
  cmd->add_option("input", args->input, "scene.json, model.obj, builtin:NAME or scene.rcimg")
      ->required();
  cmd->add_option("--engine", args->engine,
                  "golden (the bit-exact model), embree, rtl (the verilated core, fp24 only) or "
                  "board (the verilated board build: ROMs, on-chip ray generation)")
      ->capture_default_str();
  cmd->add_option("--size", args->size, "frame size WxH (default: the scene's)");
  cmd->add_option("--lighting", args->lighting,
                  "headlight (the core's shading) or scene (the scene's lights with shadow, "
                  "mirror and refraction rays; the board: the lit board build; a scene without "
                  "lights keeps the headlight)")
      ->capture_default_str();
  cmd->add_option(
         "--bounces", args->bounces,
         "with --lighting scene: the depth of each pixel's tree of mirror and refraction rays (0: "
         "none; at most " +
             std::to_string(spec::kLightBounceLimit) + ")")
      ->capture_default_str()
      ->check(kDigits)
      ->each([args](const std::string&) { args->bounces_given = true; });
  cmd->add_option("--ray-source", args->ray_source,
                  "host (double-precision camera, rounded once; the default) or raygen (the "
                  "board's ray generation unit: fp arithmetic from camera registers; the default "
                  "with --engine board)");
  auto* cam =
      cmd->add_option("--camera", args->camera, "eye=X,Y,Z:look=X,Y,Z[:up=X,Y,Z][:fov=DEG]");
  cmd->add_flag("--auto-camera", args->auto_camera, "place the camera from the scene bounds")
      ->excludes(cam);
  cmd->add_option("-o,--output", args->output, "image to write (PNG, EXR, ...)")->required();
  cmd->add_option("--hits", args->hits, "hits file to write (docs/architecture.md)");
  cmd->add_option("--stats", args->stats, "statistics JSON to write");
  cmd->add_option("--reference", args->reference,
                  "also render with this engine and report hit agreement and PSNR");
  cmd->add_option("--diff", args->diff,
                  "with --reference: write the hit difference image; with --check: the exact "
                  "difference image (default: OUTPUT.diff.png)");
  cmd->add_option("--format", args->format, "number format for scene inputs: 7/16 or 8/23")
      ->capture_default_str();
  cmd->add_option("--models-path", args->models_path, "directories searched for meshes");
  cmd->add_option("--threads", args->threads,
                  "golden and embree: host threads (0: all; at most " +
                      std::to_string(kMaxRenderThreads) + ")")
      ->capture_default_str()
      ->check(kDigits & CLI::Range(0u, kMaxRenderThreads));
  cmd->add_flag("-q,--quiet", args->quiet, "no progress bar or summary");
  cmd->add_flag(
      "--check", args->check,
      "with --engine rtl or board: also render with the golden model and compare every pixel "
      "and the counters bit for bit (exit status 1 on a mismatch)");
  cmd->add_option("--latency", args->latency, "rtl: memory latency in cycles, every port")
      ->capture_default_str()
      ->check(kDigits & CLI::Range(1u, 100000u));
  cmd->add_option("--stall-seed", args->stall_seed,
                  "rtl: seeded random memory stalls, packet gaps and framebuffer back-pressure "
                  "(0: none)")
      ->capture_default_str()
      ->check(kDigits);
  cmd->add_option("--threads-rtl", args->threads_rtl,
                  "rtl: the core's packet threads: default (docs/spec.toml [core] threads), 1, 16 "
                  "or 64 (16 and 64: models `make bench-core` builds)")
      ->capture_default_str();
  cmd->add_option("--isect-interval-rtl", args->isect_interval_rtl,
                  "rtl: cycles per ray-triangle test of the core's intersection unit: default "
                  "(docs/spec.toml [core] isect_interval) or 1 (two transform units)")
      ->capture_default_str();
  cmd->add_option("--setup-units-rtl", args->setup_units_rtl,
                  "rtl: the core's ray set-up units: default (docs/spec.toml [core] setup_units), "
                  "1 or 2 (models `make bench-core` builds)")
      ->capture_default_str();
  cmd->add_option("--secondary", args->secondary,
                  "rtl with --lighting scene: chip (the tree controller rc_tracer makes the "
                  "shadow, mirror and refraction rays and sums the colours on chip; the default "
                  "core and --threads-rtl 1, at most " +
                      std::to_string(spec::kLightMaxLights) +
                      " lights) or host (the core alone traces them in passes, the light terms "
                      "and directions on the host; every model)")
      ->capture_default_str()
      ->each([args](const std::string&) { args->secondary_given = true; });
  cmd->add_option("--trace", args->trace, "rtl: write an FST waveform");
  cmd->add_option("--trace-window", args->trace_window, "rtl: trace only cycles FIRST:LAST");
  cmd->add_option("--watchdog", args->watchdog,
                  "rtl: fail after this many cycles without any handshake (at least 1; the "
                  "board: ten times as many)")
      ->capture_default_str()
      ->check(kDigits & CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  cmd->callback([cmd, args, action] {
    for (const char* name : {"--latency", "--stall-seed", "--threads-rtl", "--isect-interval-rtl",
                             "--setup-units-rtl", "--secondary", "--trace", "--trace-window"})
      if (cmd->get_option(name)->count() > 0) args->rtl_options_given.push_back(name);
    *action = [args] { return run_render(*args); };
  });
}

}  // namespace rc::app
