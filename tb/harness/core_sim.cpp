// The harness around the verilated core: instantiations for the build's three core models.
#include "core_sim.hpp"

#include "Vrc_core.h"
#include "Vrc_core___024root.h"
#include "Vrc_core_i1.h"
#include "Vrc_core_i1___024root.h"
#include "Vrc_core_t1.h"
#include "Vrc_core_t1___024root.h"
#include "core_sim_impl.hpp"

namespace rc::harness {

template <>
std::string thread_states(const Vrc_core& m) {
  return describe_thread_states(m.rootp->rc_core__DOT__st_q,
                                static_cast<uint32_t>(spec::kCoreThreads));
}
template <>
std::string thread_states(const Vrc_core_t1& m) {
  return describe_thread_states(m.rootp->rc_core__DOT__st_q, 1u);
}

template <>
std::string thread_states(const Vrc_core_i1& m) {
  return describe_thread_states(m.rootp->rc_core__DOT__st_q,
                                static_cast<uint32_t>(spec::kCoreThreads));
}

template class CoreSim<Vrc_core>;
template class CoreSim<Vrc_core_t1>;
template class CoreSim<Vrc_core_i1>;

CoreSimResult render_rtl(const scene::SceneImage& image, const RenderOptions& render,
                         const CoreSimOptions& options, CoreModel model) {
  if (model == CoreModel::kThreads1) return CoreSim<Vrc_core_t1>(image, options).render(render);
  if (model == CoreModel::kIsect1) return CoreSim<Vrc_core_i1>(image, options).render(render);
  return CoreSim<Vrc_core>(image, options).render(render);
}

}  // namespace rc::harness
