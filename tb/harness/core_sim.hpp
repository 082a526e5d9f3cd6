// The harness around the verilated core (rtl/core/rc_core.sv): resets and clocks it, serves its
// five memory ports from a memory image through rc::harness::MemoryPort, feeds it the packets of
// the shared ray source (tb/golden/render.hpp PacketSource), collects its framebuffer writes
// into an rc::Frame with exact hit records, reads its performance counters, and watches for hangs.
//
// The simulation class is a template on the Verilator model type (core_sim_impl.hpp holds its
// definition); core_sim.cpp instantiates it for the two models the build verilates: Vrc_core
// (default Threads) and Vrc_core_t1 (Threads = 1). render_rtl() picks one of them.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare.hpp"
#include "image.hpp"
#include "memory_model.hpp"
#include "rc_constants.hpp"
#include "render.hpp"

namespace rc::harness {

// The core's memory ports, in this order everywhere (options, statistics, messages).
enum CorePort : int { kPortNodes = 0, kPortLists, kPortTriangles, kPortShading, kPortMaterials };
constexpr int kCorePorts = 5;
const char* core_port_name(int port);

constexpr int kCorePerfCount = static_cast<int>(spec::kCorePerfCount);

// Where render_rtl() makes a lit frame's secondary rays (RenderOptions::lighting kScene, an
// image with lights): on chip, by the tree controller around the core (rtl/core/rc_tracer.sv,
// the default), or on the host in passes of the core alone (light_rtl(): each level's shadow,
// mirror and refraction packets a pass of their own, with each pass's figures).
enum class SecondaryPath { kOnChip, kHost };

struct CoreSimOptions {
  SecondaryPath secondary = SecondaryPath::kOnChip;
  // Per port timing (latency, rate limits, random stalls with their seeds).
  std::array<MemoryParams, kCorePorts> memory{};
  // Non-zero: a fixed recipe of seeded random stalls on every port (request stalls, extra delays,
  // withheld responses; seeds derived from this one per port), seeded random gaps in the packet
  // stream and random low periods of fb_ready_i. Overrides the stall fields of `memory`.
  uint64_t stall_seed = 0;
  // The run fails when no handshake completes on any port for this many cycles.
  uint64_t watchdog_cycles = 200000;
  // FST waveform (empty: none), dumped only for cycles first .. last (both inclusive).
  std::string trace_path;
  uint64_t trace_first = 0;
  uint64_t trace_last = std::numeric_limits<uint64_t>::max();
  bool progress = false;  // progress line on stderr
  // What the progress line counts: a camera frame's pixels, or a secondary pass's rays.
  std::string progress_label = "rtl: pixels";
};

// splitmix64's finaliser: per-port seeds from one seed.
inline uint64_t mix_seed(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// The core's five memory ports for an image, with the given timing: nodes, lists, triangles and
// shading by section, and the materials' kd fields (12 bytes of each 128-byte record). The node
// port answers spec::kCoreNodeRspRecords (2) consecutive records per request (record i and
// i + 1, docs/memory-format.md), the others one record.
std::vector<std::unique_ptr<MemoryPort>> make_core_ports(
    const scene::SceneImage& image, const std::array<MemoryParams, kCorePorts>& memory);

// rc_tracer's two lighting ports (lshd_*, lmat_*): the shading section, and each material's
// bytes [image_material] kd .. eta + 4, with the given timing (their own stall seeds).
std::vector<std::unique_ptr<MemoryPort>> make_light_ports(const scene::SceneImage& image,
                                                          const MemoryParams& shading,
                                                          const MemoryParams& materials);

// The core's root_node_i (and the board's root registers): node 0's record, zero when the node
// section is empty.
uint64_t root_node_record(const scene::SceneImage& image);

// The golden model's counters from the core's performance counters (by number) and error_o.
Counters counters_from_perf(const std::array<uint64_t, kCorePerfCount>& perf, uint32_t error_bits);

// The core's counters of one ray kind (docs/spec.toml [core_perf] primary_rays ..).
struct KindCounters {
  uint64_t rays = 0, traversal_steps = 0, triangle_tests = 0;
};
constexpr int kRayKinds = static_cast<int>(spec::kRayKindCount);
// A kind's name in the statistics: its [ray_kind] key (primary, shadow, bounce, refract).
std::string ray_kind_name(int kind);
// Per kind, by its [ray_kind] value.
std::array<KindCounters, kRayKinds> kind_counters(const std::array<uint64_t, kCorePerfCount>& perf);

// What is wrong with a run's per-kind counters, one line per problem: each kind's rays must be
// the rays of the packets of that kind fed to the core (`rays_fed`, by kind), a kind without rays
// must have no traversal steps or triangle tests, and each event's kinds must sum to the core's
// total of it.
// A kind whose bit is set in `on_chip_kinds` is made on chip (rc_tracer's shadow, mirror and
// refraction packets): its rays are not fed, so only its other checks apply.
std::vector<std::string> kind_problems(const std::array<uint64_t, kCorePerfCount>& perf,
                                       const std::array<uint64_t, kRayKinds>& rays_fed,
                                       uint32_t on_chip_kinds = 0);
// The kinds rc_tracer makes on chip: shadow, mirror and refraction.
inline constexpr uint32_t kTracerKinds = 1u << static_cast<unsigned>(spec::kRayKindShadow) |
                                         1u << static_cast<unsigned>(spec::kRayKindBounce) |
                                         1u << static_cast<unsigned>(spec::kRayKindRefract);

// The fewest cycles a core needs for a frame with these counters, the ideal of the efficiency
// figure (efficiency = ideal_cycles / cycles): its four traversal sub-units take one step each
// per cycle, its intersection unit one ray-triangle test every isect_interval cycles.
uint64_t ideal_cycles(const Counters& c,
                      uint32_t isect_interval = static_cast<uint32_t>(spec::kCoreIsectInterval));

// Applies the stall recipe of `stall_seed` to the port parameters (keeps latency and limits).
void apply_stall_recipe(std::array<MemoryParams, kCorePorts>& memory, uint64_t stall_seed);

// The passes of one kind of secondary packets (scene lighting), summed: packets, cycles, the
// performance counters (max_stack: the largest), error bits and run_problems() of each pass.
struct SecondaryPasses {
  uint64_t passes = 0;
  uint64_t packets = 0;
  uint64_t cycles = 0;
  std::array<uint64_t, kCorePerfCount> perf{};
  uint32_t error_bits = 0;
  std::vector<std::string> problems;
};

struct CoreSimResult {
  Frame frame;          // rgb, hit_tri, hit_t, exact hits; counters from the core's perf counters
  uint64_t cycles = 0;  // clock cycles after reset
  uint32_t error_bits = 0;                      // error_o (all CoreStatus bits)
  bool idle = false;                            // idle_o at the end
  std::array<uint64_t, kCorePerfCount> perf{};  // every perf counter, by number
  std::array<MemoryStats, kCorePorts> memory{};
  uint64_t packets_fed = 0;
  std::array<uint64_t, kRayKinds> rays_fed{};  // the rays of the packets fed, by kind
  uint64_t fb_writes = 0;
  uint64_t writes_due = 0;  // one per existing ray (a camera frame: its pixels)
  // Per packet (row by row) the cycle the core took it; per pixel the cycle of its framebuffer
  // write: where to look in a waveform (docs/debugging.md).
  std::vector<uint64_t> packet_cycle, pixel_cycle;
  uint64_t misses_with_payload = 0;  // misses reported with a non-zero tri/t/u/v (must be 0)
  double seconds = 0.0;              // wall time of the simulation
  double cycles_per_second = 0.0;    // simulated cycles per wall second

  // Scene lighting (RenderOptions::lighting kScene, an image with lights; docs/architecture.md,
  // "Lighting", "Reflection" and "Refraction"): the frame above is the lit one (rgb, light_mask,
  // bounce_tri, refract_tri and the shadow, bounce and refract counters) and the fields above are
  // the primary pass's. The secondary packets are made from the core's hits, level by level of
  // the pixels' ray trees, and traced by the core in passes of their own: each level's shadow
  // packets, then its mirror packets, then its refraction packets (their figures here, summed per
  // kind); the light terms, the directions and the pixel sums are the golden model's functions,
  // on the host (rc_core has no light unit; rc_tracer, below, has one).
  bool lit = false;
  SecondaryPasses shadow, bounce, refract;
  // A tree controller's run (rc_tracer): the frame is lit on chip (rgb, light_mask, bounce_tri,
  // refract_tri from its writes), its counters are the core's totals over every kind (perf), and
  // bit k set: kind k's packets were made on chip (not fed).
  uint32_t on_chip_kinds = 0;
};

// What a run must show besides a frame and counters equal to the golden model's: the core idle at
// the end, no miss carrying a hit record, the core's own count of framebuffer writes equal to the
// frame's pixels, no error bit the golden model does not have (the watchdog, unknown bits), the
// per-kind counters right for the packets fed (kind_problems(), every pass's). One
// line per problem, empty for a clean run. `raycore render --check` and the regression tests both
// judge a run by it.
std::vector<std::string> run_problems(const CoreSimResult& r);

// A run that went wrong: a hang (watchdog), the core's watchdog bit, a pixel written twice or not
// at all, a write to a pixel that does not exist, a memory protocol violation. The message names
// the cycle and the state of every port.
class CoreSimError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The kind of a packet (rc_core's pkt_kind_i, docs/spec.toml [ray_kind]).
enum class RayKind : uint8_t {
  kPrimary = spec::kRayKindPrimary,
  kShadow = spec::kRayKindShadow,
  kBounce = spec::kRayKindBounce,
  kRefract = spec::kRayKindRefract,
};

// A packet as the core's packet port takes it (rc_core's pkt_*): up to four rays (mask bit r: ray
// r exists), each writing framebuffer pixel `slot[r]`; a secondary packet (a shadow, bounce or
// refract packet: docs/architecture.md, "Lighting", "Reflection", "Refraction") also gives each ray
// its limit t_hi and the triangle it starts on.
struct CorePacket {
  uint32_t mask = 0;
  std::array<Ray<fp24>, kPacketRays> rays{};
  std::array<uint32_t, kPacketRays> slot{};
  RayKind kind = RayKind::kPrimary;
  std::array<fp24, kPacketRays> t_hi{};
  std::array<int32_t, kPacketRays> start_tri{-1, -1, -1, -1};
};

// The packet of `kind` of the rays in `mask` of a secondary packet's rays and limits, packet
// `index` of a pass: ray r writes framebuffer pixel 4 * index + r of a 4-wide frame.
CorePacket secondary_packet(RayKind kind, uint32_t mask,
                            const std::array<Ray<fp24>, kPacketRays>& rays,
                            const SecondaryLimits<fp24>& lim, size_t index);

// The simulation of one verilated core model. Not copyable; one run per object.
template <class Model>
class CoreSim {
 public:
  CoreSim(const scene::SceneImage& image, const CoreSimOptions& options);
  ~CoreSim();
  CoreSim(const CoreSim&) = delete;
  CoreSim& operator=(const CoreSim&) = delete;

  // Renders the frame of `render` (size, camera, background; threads and progress are ignored).
  // Throws CoreSimError for a failed run.
  CoreSimResult render(const RenderOptions& render);

  // Traces the given packets in their order into a frame of width x height pixels (each existing
  // ray writes its slot once; no two rays share one), with t_eps_i = t_eps. The frame's rgb is
  // what the core wrote (0 for a shadow ray), its hits the rays' records. Throws
  // std::invalid_argument for a slot outside the frame or shared, CoreSimError for a failed run.
  CoreSimResult trace(const std::vector<CorePacket>& packets, uint32_t width, uint32_t height,
                      fp24 t_eps);

 private:
  static constexpr uint64_t kNoOwner = std::numeric_limits<uint64_t>::max();
  // A run's packets: packet(k, p) fills packet k of `packets`.
  struct Feed {
    uint32_t width = 0, height = 0;
    uint64_t packets = 0;
    std::function<void(uint64_t, CorePacket&)> packet;
    std::array<uint8_t, 3> background{};
    fp24 t_eps = fp24::zero();
    uint32_t max_bounces = 0;  // a tree controller's depth (render())
  };
  CoreSimResult run(const Feed& feed);
  struct State;
  std::unique_ptr<State> s_;
};

// Which verilated model render_rtl() runs: the default parameters, Threads = 1, 16 or 64 (the
// default is docs/spec.toml [core] threads), IsectInterval = 1, or SetupUnits = 1 or 2 (the
// default is [core] setup_units).
enum class CoreModel { kDefault, kThreads1, kThreads16, kThreads64, kIsect1, kSetup1, kSetup2 };

// The intersection interval (cycles per ray-triangle test) of a model.
inline uint32_t isect_interval(CoreModel m) {
  return m == CoreModel::kIsect1 ? 1u : static_cast<uint32_t>(spec::kCoreIsectInterval);
}

// The packet threads of a model.
inline uint32_t model_threads(CoreModel m) {
  switch (m) {
    case CoreModel::kThreads1: return 1u;
    case CoreModel::kThreads16: return 16u;
    case CoreModel::kThreads64: return 64u;
    default: return static_cast<uint32_t>(spec::kCoreThreads);
  }
}

// The ray set-up units of a model.
inline uint32_t model_setup_units(CoreModel m) {
  switch (m) {
    case CoreModel::kSetup1: return 1u;
    case CoreModel::kSetup2: return 2u;
    default: return static_cast<uint32_t>(spec::kCoreSetupUnits);
  }
}

// The utilisation of each of the core's units in a run: the operations it took times the cycles
// each occupies it, over the run's cycles (docs/architecture.md, "Counters"): ray set-up, rays x
// setup_interval / setup_units (each rc_ray_setup takes a ray per [core] setup_interval cycles);
// traversal, inner-node visits (a node step of the four sub-units, whatever the number of active
// rays); list, list requests; intersection, ray-triangle tests x isect_interval; shading, shaded
// rays. busiest is the largest.
struct UnitUtilisation {
  double setup = 0, trav = 0, list = 0, isect = 0, shade = 0;
  const char* busiest_name = "";
  double busiest = 0;
};
UnitUtilisation unit_utilisation(const std::array<uint64_t, kCorePerfCount>& perf, uint64_t cycles,
                                 uint32_t isect_interval, uint32_t setup_units);

// Why render_rtl() cannot make the frame's secondary rays on chip (empty: it can, or the frame
// has none): the tree controller is built around the default core and the core with one thread
// (the modules rc_tracer and rc_tracer_t1), and lights [light] max_lights lights at most.
std::string on_chip_problem(const scene::SceneImage& image, const RenderOptions& render,
                            CoreModel model);

// The golden model's frame's counters against a run's (counter_differences(): `required` marks
// the ones that must match). A frame without scene lighting: its counters. Lit with host passes
// (CoreSimResult::shadow ..): each kind's counters against the golden model's, the names
// prefixed by the kind ("shadow rays"). Lit on chip (on_chip_kinds): the core's counters
// count every packet it traced, so they are compared with the golden model's four kinds summed
// ("all kinds rays"), and each kind's rays, traversal steps and triangle tests from the core's
// per-kind counters with the golden model's ("shadow rays"); the other counters (node fetches,
// stack operations ..) are not counted per kind.
std::vector<CounterDifference> frame_counter_differences(const Frame& gold, const CoreSimResult& r);

// Renders an fp24 image through the verilated core; with scene lighting, its secondary rays on
// chip (rc_tracer) or in host passes (CoreSimOptions::secondary). Throws scene::Error for an
// image in another format or secondary rays on chip that on_chip_problem() refuses, and
// CoreSimError for a failed run.
CoreSimResult render_rtl(const scene::SceneImage& image, const RenderOptions& render,
                         const CoreSimOptions& options, CoreModel model = CoreModel::kDefault);

// The hit of a primary ray from the core's hit record (tri, t, u, v) and d'z, computed again with
// the intersection unit's expression (rc::transformed_dz()): what the lighting needs.
Hit<fp24> hit_from_record(const Geometry<fp24>& g, const Ray<fp24>& ray, const HitRecord& rec);

// Traces explicit packets through the verilated core (CoreSim::trace()).
CoreSimResult trace_rtl(const scene::SceneImage& image, const std::vector<CorePacket>& packets,
                        uint32_t width, uint32_t height, fp24 t_eps, const CoreSimOptions& options,
                        CoreModel model = CoreModel::kDefault);

}  // namespace rc::harness
