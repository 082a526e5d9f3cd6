// The harness around the verilated core: the default model is linked in; the other
// configurations (Threads = 1, 16, 64, IsectInterval = 1, SetupUnits = 1, 2) are modules loaded
// when a run asks for them (model_module.hpp, core_module.cpp).
#include "core_sim.hpp"

#include "Vrc_core.h"
#include "core_sim_impl.hpp"
#include "error.hpp"
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

}  // namespace

CoreSimResult render_rtl(const scene::SceneImage& image, const RenderOptions& render,
                         const CoreSimOptions& options, CoreModel model) {
  if (model == CoreModel::kThreads1) return render_module("rc_core_t1", image, render, options);
  if (model == CoreModel::kThreads16) return render_module("rc_core_t16", image, render, options);
  if (model == CoreModel::kThreads64) return render_module("rc_core_t64", image, render, options);
  if (model == CoreModel::kIsect1) return render_module("rc_core_i1", image, render, options);
  if (model == CoreModel::kSetup1) return render_module("rc_core_s1", image, render, options);
  if (model == CoreModel::kSetup2) return render_module("rc_core_s2", image, render, options);
  return CoreSim<Vrc_core>(image, options).render(render);
}

}  // namespace rc::harness
