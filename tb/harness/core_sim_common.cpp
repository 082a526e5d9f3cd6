// The parts of the core harness that do not depend on a verilated model (core_sim.hpp).
#include "core_sim.hpp"

namespace rc::harness {

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

}  // namespace rc::harness
