// The harness around the verilated core: the default model is linked in; the other
// configurations (Threads = 1, 16, 64, IsectInterval = 1, SetupUnits = 1, 2) and the tree
// controller around the default core and the one-thread core (rc_tracer, rc_tracer_t1) are
// modules loaded when a run asks for them (model_module.hpp, core_module.cpp).
#include "core_sim.hpp"

#include <algorithm>

#include "Vrc_core.h"
#include "core_sim_impl.hpp"
#include "error.hpp"
#include "geometry.hpp"
#include "model_module.hpp"

namespace rc::harness {

template <>
std::string thread_states(const Vrc_core& m) {
  return describe_thread_states(m.dbg_thread_state_o, static_cast<uint32_t>(spec::kCoreThreads));
}

template class CoreSim<Vrc_core>;

namespace {

using ModuleRender = int(const scene::SceneImage*, const RenderOptions*, const CoreSimOptions*,
                         CoreSimResult*, std::string*);

CoreSimResult render_module(const char* module, const scene::SceneImage& image,
                            const RenderOptions& render, const CoreSimOptions& options) {
  auto* fn = reinterpret_cast<ModuleRender*>(module_symbol(module, "rc_core_module_render"));
  CoreSimResult r;
  std::string error;
  rethrow_module_status<CoreSimError>(fn(&image, &render, &options, &r, &error), error);
  return r;
}

using ModuleTrace = int(const scene::SceneImage*, const std::vector<CorePacket>*, uint32_t,
                        uint32_t, uint32_t, const CoreSimOptions*, CoreSimResult*, std::string*);

CoreSimResult trace_module(const char* module, const scene::SceneImage& image,
                           const std::vector<CorePacket>& packets, uint32_t width, uint32_t height,
                           fp24 t_eps, const CoreSimOptions& options) {
  auto* fn = reinterpret_cast<ModuleTrace*>(module_symbol(module, "rc_core_module_trace"));
  CoreSimResult r;
  std::string error;
  rethrow_module_status<CoreSimError>(
      fn(&image, &packets, width, height, t_eps.bits(), &options, &r, &error), error);
  return r;
}

// The module of a model other than the default (nullptr for the default, linked in).
const char* model_module(CoreModel model) {
  switch (model) {
    case CoreModel::kThreads1: return "rc_core_t1";
    case CoreModel::kThreads16: return "rc_core_t16";
    case CoreModel::kThreads64: return "rc_core_t64";
    case CoreModel::kIsect1: return "rc_core_i1";
    case CoreModel::kSetup1: return "rc_core_s1";
    case CoreModel::kSetup2: return "rc_core_s2";
    default: return nullptr;
  }
}

// The tree controller's module around a model's core (nullptr: none is built).
const char* tracer_module(CoreModel model) {
  switch (model) {
    case CoreModel::kDefault: return "rc_tracer";
    case CoreModel::kThreads1: return "rc_tracer_t1";
    default: return nullptr;
  }
}

// One pass of secondary packets of `kind` through the core: packet j's ray r writes slot 4j + r
// of a 4-wide frame. Adds its figures to `sum` and returns the run.
CoreSimResult secondary_pass(const scene::SceneImage& image, const std::vector<CorePacket>& packets,
                             fp24 t_eps, const CoreSimOptions& options, CoreModel model,
                             const char* kind, SecondaryPasses& sum) {
  CoreSimOptions so = options;
  so.trace_path.clear();  // a waveform covers the primary pass
  so.progress_label =
      std::string("rtl ") + kind + " pass " + std::to_string(sum.passes + 1) + ": rays";
  CoreSimResult s =
      trace_rtl(image, packets, 4, static_cast<uint32_t>(packets.size()), t_eps, so, model);
  ++sum.passes;
  sum.packets += packets.size();
  sum.cycles += s.cycles;
  for (size_t i = 0; i < sum.perf.size(); ++i)
    sum.perf[i] = i == static_cast<size_t>(spec::kCorePerfMaxStack)
                      ? std::max(sum.perf[i], s.perf[i])
                      : sum.perf[i] + s.perf[i];
  sum.error_bits |= s.error_bits;
  for (const std::string& p : run_problems(s)) sum.problems.push_back(p);
  return s;
}

// A secondary packet that ended with an error: the core writes colour 1 for each of its rays.
bool secondary_failed(const Frame& f, size_t j, uint32_t mask) {
  for (uint32_t r = 0; r < kPacketRays; ++r)
    if ((mask >> r & 1u) && f.rgb[3 * (4 * j + r)] != 0) return true;
  return false;
}

// Scene lighting through the core (CoreSimResult's lit fields): the pixels' ray trees, level by
// level from the primary frame r's hits; per level the shadow packets, then the mirror packets,
// then the refraction packets, each a pass of the same model; each pixel's sums.
void light_rtl(const scene::SceneImage& image, const RenderOptions& render,
               const CoreSimOptions& options, CoreModel model, CoreSimResult& r) {
  const Geometry<fp24> g = load_geometry<fp24>(image);
  const LitParams<fp24> lp = lit_params<fp24>(render.max_bounces, render.background);
  const PacketSource<fp24> gen(render.camera, render.width, render.height, render.ray_source);
  const uint32_t pw = (render.width + 1) / 2, ph = (render.height + 1) / 2;
  Frame& f = r.frame;
  r.lit = true;
  f.shadow_counters = Counters{};
  f.bounce_counters = Counters{};
  f.refract_counters = Counters{};

  // A packet of the current level: its primary packet and its work.
  struct Open {
    size_t primary;
    LitWork<fp24> work;
  };
  std::vector<LitSums> sums(static_cast<size_t>(pw) * ph);
  std::vector<Open> level;
  for (uint32_t py = 0; py < ph; ++py)
    for (uint32_t px = 0; px < pw; ++px) {
      std::array<Ray<fp24>, kPacketRays> rays;
      std::array<Hit<fp24>, kPacketRays> hits;
      const uint32_t mask = gen.packet(px, py, rays);
      for (uint32_t k = 0; k < kPacketRays; ++k) {
        if (!(mask >> k & 1u)) continue;
        const size_t pix =
            static_cast<size_t>(2 * py + (k >> 1)) * render.width + 2 * px + (k & 1u);
        hits[k] = hit_from_record(g, rays[k], f.hits.at(pix));
      }
      level.push_back({static_cast<size_t>(py) * pw + px, lit_work(g, rays, mask, hits, lp)});
    }

  for (uint32_t depth = 0; !level.empty(); ++depth) {
    // The level's shadow packets: a ray reached the light when it has no hit and its packet no
    // error (colour 1, rc_core), the golden model's shadow_reached().
    std::vector<CorePacket> packets;
    for (const Open& o : level)
      for (const ShadowPacket<fp24>& sp : o.work.shadows)
        packets.push_back(
            secondary_packet(RayKind::kShadow, sp.mask, sp.rays, sp.lim, packets.size()));
    std::vector<uint32_t> reached(packets.size(), 0);
    if (!packets.empty()) {
      const CoreSimResult s =
          secondary_pass(image, packets, g.t_eps, options, model, "shadow", r.shadow);
      f.shadow_counters.add(s.frame.counters);
      for (size_t j = 0; j < packets.size(); ++j) {
        std::array<Hit<fp24>, kPacketRays> hits;
        for (uint32_t k = 0; k < kPacketRays; ++k)
          if (packets[j].mask >> k & 1u)
            hits[k] = hit_from_record(g, packets[j].rays[k], s.frame.hits[4 * j + k]);
        const bool failed = secondary_failed(s.frame, j, packets[j].mask);
        reached[j] = shadow_reached(packets[j].mask, failed ? 1u : 0u, hits);
      }
    }
    size_t next = 0;  // the packet's first shadow packet
    for (const Open& o : level) {
      const auto first = reached.begin() + static_cast<std::ptrdiff_t>(next);
      const std::vector<uint32_t> mine(first,
                                       first + static_cast<std::ptrdiff_t>(o.work.shadows.size()));
      next += o.work.shadows.size();
      lit_accumulate(o.work, mine, depth, sums[o.primary]);
    }

    // The level's mirror packets, then its refraction packets, and from their hits the next
    // level.
    std::vector<Open> deeper;
    for (const TreeRay kind : {TreeRay::kMirror, TreeRay::kRefract}) {
      const bool mirror = kind == TreeRay::kMirror;
      std::vector<CorePacket> bpackets;
      std::vector<const Open*> parent;
      for (const Open& o : level) {
        const BouncePacket<fp24>& b = mirror ? o.work.bounce : o.work.refract;
        if (b.mask == 0) continue;
        bpackets.push_back(secondary_packet(mirror ? RayKind::kBounce : RayKind::kRefract, b.mask,
                                            b.rays, b.lim, bpackets.size()));
        parent.push_back(&o);
      }
      if (bpackets.empty()) continue;
      const CoreSimResult s =
          secondary_pass(image, bpackets, g.t_eps, options, model, mirror ? "mirror" : "refraction",
                         mirror ? r.bounce : r.refract);
      (mirror ? f.bounce_counters : f.refract_counters).add(s.frame.counters);
      for (size_t j = 0; j < bpackets.size(); ++j) {
        const BouncePacket<fp24>& b = mirror ? parent[j]->work.bounce : parent[j]->work.refract;
        const size_t primary = parent[j]->primary;
        if (secondary_failed(s.frame, j, b.mask)) {
          if (depth == 0) lit_bounce_failed(kind, b.mask, sums[primary]);
          continue;
        }
        std::array<Hit<fp24>, kPacketRays> hits;
        for (uint32_t k = 0; k < kPacketRays; ++k)
          if (b.mask >> k & 1u) hits[k] = hit_from_record(g, b.rays[k], s.frame.hits[4 * j + k]);
        deeper.push_back(
            {primary, lit_work(g, b.rays, b.mask, hits, lp, depth + 1, &b.weight, kind)});
      }
    }
    level = std::move(deeper);
  }

  f.light_mask.assign(static_cast<size_t>(f.width) * f.height, 0);
  f.bounce_tri.assign(static_cast<size_t>(f.width) * f.height, -2);
  f.refract_tri.assign(static_cast<size_t>(f.width) * f.height, -2);
  for (uint32_t py = 0; py < ph; ++py)
    for (uint32_t px = 0; px < pw; ++px) {
      const LitPacket lpk = lit_finish(sums[static_cast<size_t>(py) * pw + px]);
      const LitSums& ls = sums[static_cast<size_t>(py) * pw + px];
      for (uint32_t k = 0; k < kPacketRays; ++k) {
        const uint32_t x = 2 * px + (k & 1u), y = 2 * py + (k >> 1);
        if (x >= render.width || y >= render.height) continue;
        const size_t pix = static_cast<size_t>(y) * render.width + x;
        f.light_mask[pix] = lpk.lights[k];
        f.bounce_tri[pix] = lpk.bounce_tri[k];
        f.refract_tri[pix] = lpk.refract_tri[k];
        if (ls.hit_mask >> k & 1u) std::copy(lpk.rgb[k].begin(), lpk.rgb[k].end(), &f.rgb[3 * pix]);
      }
    }
}

}  // namespace

CorePacket secondary_packet(RayKind kind, uint32_t mask,
                            const std::array<Ray<fp24>, kPacketRays>& rays,
                            const SecondaryLimits<fp24>& lim, size_t index) {
  CorePacket p;
  p.kind = kind;
  p.mask = mask;
  p.rays = rays;
  p.t_hi = lim.t_hi;
  p.start_tri = lim.exclude;
  for (uint32_t r = 0; r < kPacketRays; ++r) p.slot[r] = static_cast<uint32_t>(4 * index + r);
  return p;
}

std::string on_chip_problem(const scene::SceneImage& image, const RenderOptions& render,
                            CoreModel model) {
  if (render.lighting != Lighting::kScene || image.light_count() == 0) return "";
  if (!tracer_module(model))
    return "secondary rays on chip: the tree controller (rc_tracer) is built around the default "
           "core and the core with one thread only, not this model (trace them on the host: "
           "--secondary host)";
  if (image.light_count() > static_cast<size_t>(spec::kLightMaxLights))
    return "secondary rays on chip: the tree controller holds " +
           std::to_string(spec::kLightMaxLights) + " lights ([light] max_lights), " + image.name() +
           " has " + std::to_string(image.light_count()) +
           " (trace them on the host: --secondary host)";
  return "";
}

CoreSimResult render_rtl(const scene::SceneImage& image, const RenderOptions& render,
                         const CoreSimOptions& options, CoreModel model) {
  const bool lit = render.lighting == Lighting::kScene && image.light_count() > 0;
  if (lit && options.secondary == SecondaryPath::kOnChip) {
    if (const std::string why = on_chip_problem(image, render, model); !why.empty())
      throw scene::Error(why);
    return render_module(tracer_module(model), image, render, options);
  }
  const char* module = model_module(model);
  CoreSimResult r = module ? render_module(module, image, render, options)
                           : CoreSim<Vrc_core>(image, options).render(render);
  if (lit) light_rtl(image, render, options, model, r);
  return r;
}

CoreSimResult trace_rtl(const scene::SceneImage& image, const std::vector<CorePacket>& packets,
                        uint32_t width, uint32_t height, fp24 t_eps, const CoreSimOptions& options,
                        CoreModel model) {
  if (const char* module = model_module(model))
    return trace_module(module, image, packets, width, height, t_eps, options);
  return CoreSim<Vrc_core>(image, options).trace(packets, width, height, t_eps);
}

}  // namespace rc::harness
