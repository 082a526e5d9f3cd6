// The harness around the verilated core: the default model is linked in; the other
// configurations (Threads = 1, 16, 64, IsectInterval = 1, SetupUnits = 1, 2) are modules loaded
// when a run asks for them (model_module.hpp, core_module.cpp).
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

// Scene lighting through the core (CoreSimResult's lit fields): the shadow packets of the primary
// frame r, traced by the same model, and each pixel's sums.
void light_rtl(const scene::SceneImage& image, const RenderOptions& render,
               const CoreSimOptions& options, CoreModel model, CoreSimResult& r) {
  const Geometry<fp24> g = load_geometry<fp24>(image);
  std::vector<LitWork<fp24>> works;
  const std::vector<CorePacket> packets = shadow_core_packets(g, render, r.frame, works);
  r.lit = true;
  r.shadow_packets = packets.size();
  Frame& f = r.frame;
  f.shadow_counters = Counters{};
  std::vector<uint32_t> reached(packets.size(), 0);
  if (!packets.empty()) {
    CoreSimOptions so = options;
    so.trace_path.clear();  // a waveform covers the primary pass
    const CoreSimResult s =
        trace_rtl(image, packets, 4, static_cast<uint32_t>(packets.size()), g.t_eps, so, model);
    r.shadow_cycles = s.cycles;
    r.shadow_perf = s.perf;
    r.shadow_error_bits = s.error_bits;
    r.shadow_problems = run_problems(s);
    f.shadow_counters = s.frame.counters;
    // A ray reached the light when it has no hit and its packet no error (colour 1, rc_core).
    for (size_t j = 0; j < packets.size(); ++j)
      for (uint32_t k = 0; k < kPacketRays; ++k) {
        const size_t slot = 4 * j + k;
        if ((packets[j].mask >> k & 1u) && s.frame.hits[slot].tri < 0 && s.frame.rgb[3 * slot] == 0)
          reached[j] |= 1u << k;
      }
  }
  f.light_mask.assign(static_cast<size_t>(f.width) * f.height, 0);
  const PacketSource<fp24> gen(render.camera, render.width, render.height, render.ray_source);
  const uint32_t pw = (render.width + 1) / 2;
  size_t next = 0;  // the primary packet's first shadow packet
  for (size_t k = 0; k < works.size(); ++k) {
    const auto px = static_cast<uint32_t>(k % pw), py = static_cast<uint32_t>(k / pw);
    std::array<Ray<fp24>, kPacketRays> rays;
    const uint32_t mask = gen.packet(px, py, rays);
    const LitWork<fp24>& w = works[k];
    const auto first = reached.begin() + static_cast<std::ptrdiff_t>(next);
    const std::vector<uint32_t> mine(first, first + static_cast<std::ptrdiff_t>(w.shadows.size()));
    next += w.shadows.size();
    const LitPacket lp = lit_resolve(w, mine);
    for (uint32_t ray = 0; ray < kPacketRays; ++ray) {
      if (!(mask >> ray & 1u)) continue;
      const size_t pix =
          static_cast<size_t>(2 * py + (ray >> 1)) * render.width + 2 * px + (ray & 1u);
      f.light_mask[pix] = lp.lights[ray];
      if (w.hit_mask >> ray & 1u)
        std::copy(lp.rgb[ray].begin(), lp.rgb[ray].end(), &f.rgb[3 * pix]);
    }
  }
}

}  // namespace

CoreSimResult render_rtl(const scene::SceneImage& image, const RenderOptions& render,
                         const CoreSimOptions& options, CoreModel model) {
  const char* module = model_module(model);
  CoreSimResult r = module ? render_module(module, image, render, options)
                           : CoreSim<Vrc_core>(image, options).render(render);
  if (render.lighting == Lighting::kScene && image.light_count() > 0)
    light_rtl(image, render, options, model, r);
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
