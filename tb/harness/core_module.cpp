// One core model built as a module (model_module.hpp): the harness around the verilated rc_core
// of another configuration than the default. RC_CORE_MODEL names the model class (Vrc_core_t1,
// Vrc_core_i1), RC_CORE_MODEL_H its header, RC_CORE_MODEL_THREADS its
// Threads parameter when it is not the default (tb/harness/CMakeLists.txt). render_rtl()
// (core_sim.cpp) calls its entry point.
#include <string>

#include RC_CORE_MODEL_H
#include "core_sim_impl.hpp"
#include "error.hpp"
#include "model_module.hpp"

#ifndef RC_CORE_MODEL_THREADS
#define RC_CORE_MODEL_THREADS static_cast<uint32_t>(rc::spec::kCoreThreads)
#endif

namespace rc::harness {

template <>
std::string thread_states(const RC_CORE_MODEL& m) {
  return describe_thread_states(m.dbg_thread_state_o, RC_CORE_MODEL_THREADS);
}

template class CoreSim<RC_CORE_MODEL>;

}  // namespace rc::harness

// Renders *render of *image through the model: the result in *out, or a status and the message.
extern "C" __attribute__((visibility("default"))) int rc_core_module_render(
    const rc::scene::SceneImage* image, const rc::RenderOptions* render,
    const rc::harness::CoreSimOptions* options, rc::harness::CoreSimResult* out,
    std::string* error) {
  using namespace rc::harness;
  return run_in_module<CoreSimError>(
      error, [&] { *out = CoreSim<RC_CORE_MODEL>(*image, *options).render(*render); });
}

// Traces *packets through the model into a width x height frame (t_eps_bits: t_eps_i).
extern "C" __attribute__((visibility("default"))) int rc_core_module_trace(
    const rc::scene::SceneImage* image, const std::vector<rc::harness::CorePacket>* packets,
    uint32_t width, uint32_t height, uint32_t t_eps_bits,
    const rc::harness::CoreSimOptions* options, rc::harness::CoreSimResult* out,
    std::string* error) {
  using namespace rc::harness;
  return run_in_module<CoreSimError>(error, [&] {
    *out = CoreSim<RC_CORE_MODEL>(*image, *options)
               .trace(*packets, width, height, rc::fp24::from_bits(t_eps_bits));
  });
}
