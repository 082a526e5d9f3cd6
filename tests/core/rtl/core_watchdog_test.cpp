// The core's watchdog (rtl/core/rc_core.sv, status bit `watchdog`): the core verilated with
// Threads = 1 and WatchdogCycles = kWatchdog (Vrc_core_wd, this directory's CMakeLists.txt), run
// through the harness with one memory port slowed down:
//  - a node latency a little under the watchdog's count: no handshake for fewer than kWatchdog
//    cycles at a time, so the bit stays 0 and the frame is bit for bit the golden model's;
//  - a node latency well over it: the bit rises after exactly kWatchdog cycles without a handshake
//    on any port plus two (the error register, and the handshakes' second register level), while
//    the core waits for its node, and the
//    harness reports it (it stops the run at the first cycle the bit is set).
// The default core's count (docs/spec.toml [core] watchdog_cycles) is longer than any latency the
// harness can give, so only this model shows the bit rise.
#include <gtest/gtest.h>

#include <string>

#include "Vrc_core_wd.h"
#include "compare.hpp"
#include "core_sim_impl.hpp"
#include "cornell_input.hpp"
#include "geometry.hpp"
#include "job.hpp"

namespace rc::harness {
template <>
std::string thread_states(const Vrc_core_wd& m) {
  return describe_thread_states(m.dbg_thread_state_o, 1u);
}
template class CoreSim<Vrc_core_wd>;
}  // namespace rc::harness

namespace rc::test {
namespace {

using harness::CoreSim;
using harness::CoreSimError;
using harness::CoreSimOptions;
using harness::CoreSimResult;

constexpr uint64_t kWatchdog = 300;  // -GWatchdogCycles of Vrc_core_wd

RenderOptions small_frame() {
  RenderOptions ro = input_options(cornell());
  ro.width = 8;
  ro.height = 8;
  ro.progress = false;
  return ro;
}

TEST(CoreWatchdog, QuietForLessThanItsCountIsNoError) {
  const RenderOptions ro = small_frame();
  const Frame gold = render_golden(load_geometry<fp24>(cornell().image), ro);
  CoreSimOptions o;
  o.memory[harness::kPortNodes].latency = static_cast<uint32_t>(kWatchdog - 40);
  const CoreSimResult r = CoreSim<Vrc_core_wd>(cornell().image, o).render(ro);
  const ExactComparison cmp = compare_exact(gold, r.frame);
  EXPECT_TRUE(cmp.equal()) << cmp.differing << " of " << cmp.pixels << " pixels differ";
  EXPECT_TRUE(counter_differences(gold.counters, r.frame.counters).empty());
  EXPECT_EQ(r.error_bits, 0u);
  EXPECT_TRUE(r.idle);
  // The latency did make long quiet stretches: every node fetch waits for it.
  EXPECT_GT(r.cycles, gold.counters.nodes_fetched * (kWatchdog - 40));
}

TEST(CoreWatchdog, FiresAfterItsCount) {
  const RenderOptions ro = small_frame();
  for (uint32_t latency : {uint32_t{kWatchdog + 60}, uint32_t{5000}}) {
    SCOPED_TRACE("node latency " + std::to_string(latency));
    CoreSimOptions o;
    o.memory[harness::kPortNodes].latency = latency;
    o.watchdog_cycles = 100000;  // the harness's own hang check stays out of the way
    try {
      CoreSim<Vrc_core_wd>(cornell().image, o).render(ro);
      ADD_FAILURE() << "the watchdog bit never rose";
    } catch (const CoreSimError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("the core's watchdog bit is set"), std::string::npos) << msg;
      const std::string want = std::to_string(kWatchdog + 2) + " cycles since the last handshake";
      EXPECT_NE(msg.find(want), std::string::npos) << "want \"" << want << "\" in:\n" << msg;
      EXPECT_NE(msg.find("error_o 0x8"), std::string::npos) << "only the watchdog bit:\n" << msg;
      EXPECT_NE(msg.find("nodes port: 1 outstanding"), std::string::npos) << msg;
      // The report names the thread's state from the core's debug port: waiting for its node.
      EXPECT_NE(msg.find("threads: 0:Node\n"), std::string::npos) << msg;
    }
  }
}

}  // namespace
}  // namespace rc::test
