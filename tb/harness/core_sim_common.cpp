// The parts of the core harness that do not depend on a verilated model (core_sim.hpp).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "core_sim.hpp"

namespace rc::harness {

namespace {
// The error bits the golden model has too (malformed node, bad address, stack overflow).
constexpr uint32_t kGoldenErrorBits = kErrMalformedNode | kErrBadAddress | kErrStackOverflow;
}  // namespace

const char* core_port_name(int port) {
  switch (port) {
    case kPortNodes: return "nodes";
    case kPortLists: return "lists";
    case kPortTriangles: return "triangles";
    case kPortShading: return "shading";
    case kPortMaterials: return "materials";
    default: return "unknown";
  }
}

void apply_stall_recipe(std::array<MemoryParams, kCorePorts>& memory, uint64_t stall_seed) {
  if (stall_seed == 0) return;
  for (int i = 0; i < kCorePorts; ++i) {
    MemoryParams& p = memory[static_cast<size_t>(i)];
    p.req_stall_prob = 0.2;
    p.max_extra_delay = 24;
    p.rsp_stall_prob = 0.2;
    p.max_stall_run = 8;
    p.seed = mix_seed(stall_seed * 0x100000001b3ull + static_cast<uint64_t>(i) + 1);
  }
}

namespace {

// A port of the materials' fields from [image_material] kd on: `bytes` bytes of each record.
std::unique_ptr<MemoryPort> material_port(const scene::SceneImage& image, uint32_t bytes,
                                          const MemoryParams& params, const std::string& name) {
  const scene::SectionInfo& mat =
      image.section(static_cast<uint32_t>(spec::kImageSectionIdMaterials));
  const auto kd = static_cast<size_t>(spec::kImageMaterialKd);
  const size_t stride = mat.stride;
  std::vector<uint8_t> data(static_cast<size_t>(mat.count) * stride, 0);
  const size_t avail = static_cast<size_t>(mat.count) * stride;
  const uint8_t* first = image.bytes().data() + mat.offset;
  if (avail > kd) std::copy(first + kd, first + avail, data.begin());  // the rest stays zero
  return std::make_unique<MemoryPort>(std::move(data), mat.count, static_cast<uint32_t>(stride),
                                      bytes, params, image.name() + ":" + name);
}

}  // namespace

std::vector<std::unique_ptr<MemoryPort>> make_core_ports(
    const scene::SceneImage& image, const std::array<MemoryParams, kCorePorts>& memory) {
  std::vector<std::unique_ptr<MemoryPort>> ports;
  // Four sections by id, and the materials' kd fields.
  const uint32_t ids[4] = {static_cast<uint32_t>(spec::kImageSectionIdNodes),
                           static_cast<uint32_t>(spec::kImageSectionIdLists),
                           static_cast<uint32_t>(spec::kImageSectionIdTriangles),
                           static_cast<uint32_t>(spec::kImageSectionIdShading)};
  // The node port answers pairs of records (docs/memory-format.md, "kd nodes"), the others one.
  for (int i = 0; i < 4; ++i)
    ports.push_back(std::make_unique<MemoryPort>(
        image, ids[i], memory[static_cast<size_t>(i)],
        i == kPortNodes ? static_cast<uint32_t>(spec::kCoreNodeRspRecords) : 1u));
  ports.push_back(material_port(image, 12u, memory[kPortMaterials], "materials.kd"));
  return ports;
}

std::vector<std::unique_ptr<MemoryPort>> make_light_ports(const scene::SceneImage& image,
                                                          const MemoryParams& shading,
                                                          const MemoryParams& materials) {
  std::vector<std::unique_ptr<MemoryPort>> ports;
  MemoryParams sp = shading, mp = materials;
  sp.seed = mix_seed(sp.seed ^ 0x11647u);  // not the core's ports' stall sequences
  mp.seed = mix_seed(mp.seed ^ 0x11648u);
  ports.push_back(std::make_unique<MemoryPort>(
      image, static_cast<uint32_t>(spec::kImageSectionIdShading), sp, 1u));
  const auto len = static_cast<uint32_t>(spec::kImageMaterialEta + 4 - spec::kImageMaterialKd);
  ports.push_back(material_port(image, len, mp, "materials.lit"));
  return ports;
}

uint64_t root_node_record(const scene::SceneImage& image) {
  return image.node_count() > 0 ? image.node(0).raw : 0;
}

UnitUtilisation unit_utilisation(const std::array<uint64_t, kCorePerfCount>& perf, uint64_t cycles,
                                 uint32_t isect_interval, uint32_t setup_units) {
  const auto share = [cycles](double ops) {
    return cycles ? ops / static_cast<double>(cycles) : 0.0;
  };
  const auto p = [&perf](int64_t k) { return static_cast<double>(perf[static_cast<size_t>(k)]); };
  UnitUtilisation u;
  u.setup = share(p(spec::kCorePerfSetupBusy) * static_cast<double>(spec::kCoreSetupInterval) /
                  static_cast<double>(setup_units));
  u.trav = share(p(spec::kCorePerfTravBusy));
  u.list = share(p(spec::kCorePerfListBusy));
  u.isect = share(p(spec::kCorePerfIsectBusy) * static_cast<double>(isect_interval));
  u.shade = share(p(spec::kCorePerfShadeBusy));
  const std::pair<const char*, double> units[] = {{"setup", u.setup},
                                                  {"trav", u.trav},
                                                  {"list", u.list},
                                                  {"isect", u.isect},
                                                  {"shade", u.shade}};
  for (const auto& [name, value] : units) {
    if (value > u.busiest || u.busiest_name[0] == '\0') {
      u.busiest = value;
      u.busiest_name = name;
    }
  }
  return u;
}

Counters counters_from_perf(const std::array<uint64_t, kCorePerfCount>& perf_values,
                            uint32_t error_bits) {
  const auto perf = [&perf_values](int64_t k) { return perf_values[static_cast<size_t>(k)]; };
  Counters c;
  c.packets = perf(spec::kCorePerfPackets);
  c.rays = perf(spec::kCorePerfRays);
  c.nodes_fetched = perf(spec::kCorePerfNodesFetched);
  c.inner_visits = perf(spec::kCorePerfInnerVisits);
  c.traversal_steps = perf(spec::kCorePerfTraversalSteps);
  c.leaf_visits = perf(spec::kCorePerfLeafVisits);
  c.empty_leaves = perf(spec::kCorePerfEmptyLeaves);
  c.list_entries = perf(spec::kCorePerfListEntries);
  c.triangle_tests = perf(spec::kCorePerfTriangleTests);
  c.stack_pushes = perf(spec::kCorePerfStackPushes);
  c.stack_pops = perf(spec::kCorePerfStackPops);
  c.culled_pops = perf(spec::kCorePerfCulledPops);
  c.max_stack = perf(spec::kCorePerfMaxStack);
  c.errors = perf(spec::kCorePerfFailedPackets);
  c.error_bits = error_bits & kGoldenErrorBits;
  return c;
}

std::vector<std::string> run_problems(const CoreSimResult& r) {
  std::vector<std::string> out;
  if (r.error_bits & ~kGoldenErrorBits) {
    char buf[96];
    std::snprintf(buf, sizeof buf,
                  "error bits 0x%x outside the golden model's 0x%x (watchdog: 0x%x)",
                  r.error_bits & ~kGoldenErrorBits, kGoldenErrorBits,
                  1u << static_cast<unsigned>(spec::kCoreStatusWatchdog));
    out.push_back(buf);
  }
  if (!r.idle) out.push_back("the core is not idle at the end of the frame (idle_o low)");
  if (r.misses_with_payload)
    out.push_back(std::to_string(r.misses_with_payload) +
                  " misses carry a non-zero hit record (a miss must report tri, t, u, v = 0)");
  // The core writes once per ray it traced: the frame's, and those of the kinds made on chip
  // (a tree controller takes those writes; the harness sees one write per frame ray).
  const uint64_t counted = r.perf[static_cast<size_t>(spec::kCorePerfFbWrites)];
  uint64_t on_chip = 0;
  const std::array<KindCounters, kRayKinds> kc = kind_counters(r.perf);
  for (int k = 0; k < kRayKinds; ++k)
    if (r.on_chip_kinds >> k & 1u) on_chip += kc[static_cast<size_t>(k)].rays;
  if (counted != r.writes_due + on_chip || r.fb_writes != r.writes_due)
    out.push_back("framebuffer writes: the core counted " + std::to_string(counted) +
                  ", the harness saw " + std::to_string(r.fb_writes) + ", the frame's rays " +
                  std::to_string(r.writes_due) +
                  (on_chip ? ", the rays made on chip " + std::to_string(on_chip) : ""));
  for (const std::string& p : kind_problems(r.perf, r.rays_fed, r.on_chip_kinds)) out.push_back(p);
  for (const std::string& p : r.shadow.problems) out.push_back("shadow pass: " + p);
  for (const std::string& p : r.bounce.problems) out.push_back("bounce pass: " + p);
  for (const std::string& p : r.refract.problems) out.push_back("refract pass: " + p);
  return out;
}

std::vector<CounterDifference> frame_counter_differences(const Frame& gold,
                                                         const CoreSimResult& r) {
  const Frame& f = r.frame;
  const auto prefixed = [](const std::string& prefix, std::vector<CounterDifference> d) {
    for (CounterDifference& x : d) x.name = prefix + x.name;
    return d;
  };
  const auto append = [](std::vector<CounterDifference>& to, std::vector<CounterDifference> d) {
    to.insert(to.end(), d.begin(), d.end());
  };
  if (gold.light_mask.empty()) return counter_differences(gold.counters, f.counters);
  std::vector<CounterDifference> out;
  const std::array<const Counters*, kRayKinds> gold_kind = {
      &gold.counters, &gold.shadow_counters, &gold.bounce_counters, &gold.refract_counters};
  if (r.on_chip_kinds == 0) {
    const std::array<const Counters*, kRayKinds> rtl_kind = {
        &f.counters, &f.shadow_counters, &f.bounce_counters, &f.refract_counters};
    for (int k = 0; k < kRayKinds; ++k) {
      const auto i = static_cast<size_t>(k);
      append(out, prefixed(k == 0 ? "" : ray_kind_name(k) + " ",
                           counter_differences(*gold_kind[i], *rtl_kind[i])));
    }
    return out;
  }
  Counters all;
  for (const Counters* c : gold_kind) all.add(*c);
  append(out, prefixed("all kinds ", counter_differences(all, f.counters)));
  const std::array<KindCounters, kRayKinds> kc = kind_counters(r.perf);
  for (int k = 0; k < kRayKinds; ++k) {
    const auto i = static_cast<size_t>(k);
    const Counters& g = *gold_kind[i];
    // After an error only the rays must match (counter_differences()'s rule).
    const bool exact = all.errors == 0;
    const std::string name = ray_kind_name(k) + " ";
    const auto check = [&](const char* what, uint64_t e, uint64_t a, bool always) {
      if (e != a) out.push_back({name + what, e, a, always || exact});
    };
    check("rays", g.rays, kc[i].rays, true);
    check("traversal_steps", g.traversal_steps, kc[i].traversal_steps, false);
    check("triangle_tests", g.triangle_tests, kc[i].triangle_tests, false);
  }
  return out;
}

Hit<fp24> hit_from_record(const Geometry<fp24>& g, const Ray<fp24>& ray, const HitRecord& rec) {
  Hit<fp24> h;
  h.tri = rec.tri;
  h.t = fp24::from_bits(rec.t);
  h.u = fp24::from_bits(rec.u);
  h.v = fp24::from_bits(rec.v);
  h.dz = rec.tri >= 0 ? transformed_dz(g.tris.at(static_cast<size_t>(rec.tri)), ray.dir)
                      : fp24::zero();
  return h;
}

std::string ray_kind_name(int kind) {
  std::string name = spec::kRayKindNames[kind];
  name[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(name[0])));
  return name;
}

std::array<KindCounters, kRayKinds> kind_counters(
    const std::array<uint64_t, kCorePerfCount>& perf) {
  static_assert(spec::kCorePerfRefractTriangleTests == spec::kCorePerfPrimaryRays + 11,
                "the per-kind counters: 3 per kind, in [ray_kind] order");
  std::array<KindCounters, kRayKinds> out{};
  for (int k = 0; k < kRayKinds; ++k) {
    const auto at = [&](int e) {
      return perf[static_cast<size_t>(spec::kCorePerfPrimaryRays + 3 * k + e)];
    };
    out[static_cast<size_t>(k)] = {at(0), at(1), at(2)};
  }
  return out;
}

std::vector<std::string> kind_problems(const std::array<uint64_t, kCorePerfCount>& perf,
                                       const std::array<uint64_t, kRayKinds>& rays_fed,
                                       uint32_t on_chip_kinds) {
  std::vector<std::string> out;
  const std::array<KindCounters, kRayKinds> kc = kind_counters(perf);
  KindCounters sum;
  for (int k = 0; k < kRayKinds; ++k) {
    const KindCounters& c = kc[static_cast<size_t>(k)];
    const std::string name = ray_kind_name(k);
    if (!(on_chip_kinds >> k & 1u) && c.rays != rays_fed[static_cast<size_t>(k)])
      out.push_back(name + " rays: the core counted " + std::to_string(c.rays) + ", " +
                    std::to_string(rays_fed[static_cast<size_t>(k)]) + " were fed");
    if (c.rays == 0 && (c.traversal_steps != 0 || c.triangle_tests != 0))
      out.push_back(name + ": " + std::to_string(c.traversal_steps) + " traversal steps and " +
                    std::to_string(c.triangle_tests) + " triangle tests without rays");
    sum.rays += c.rays;
    sum.traversal_steps += c.traversal_steps;
    sum.triangle_tests += c.triangle_tests;
  }
  const std::pair<const char*, std::pair<uint64_t, int64_t>> totals[] = {
      {"rays", {sum.rays, spec::kCorePerfRays}},
      {"traversal steps", {sum.traversal_steps, spec::kCorePerfTraversalSteps}},
      {"triangle tests", {sum.triangle_tests, spec::kCorePerfTriangleTests}}};
  for (const auto& [what, v] : totals) {
    const uint64_t total = perf[static_cast<size_t>(v.second)];
    if (v.first != total)
      out.push_back(std::string(what) + ": the kinds' counters sum to " + std::to_string(v.first) +
                    ", the total is " + std::to_string(total));
  }
  return out;
}

uint64_t ideal_cycles(const Counters& c, uint32_t isect_interval) {
  return std::max(c.traversal_steps / 4, c.triangle_tests * uint64_t{isect_interval});
}

}  // namespace rc::harness
