// The synthesized netlist of the arithmetic units against the C++ model (tb/fp/fp.hpp), bit for
// bit: tests/rtl/rc_fp_units_tb.sv at fp24 and the default Stages (adder, multiplier, divider,
// square root, comparator), synthesized by Yosys synth_ecp5 into ECP5 cells and verilated with
// Yosys's ECP5 simulation models (tests/CMakeLists.txt builds it). The tests are the RTL's
// (tests/fp_rtl_test.cpp), through the same harness (tests/fp_units_harness.hpp), so the netlist
// must match the model exactly, with the same latency and valid behaviour. The exhaustive sqrt
// pass is in tests/fp_netlist_long_test.cpp (`make test-long`). (The RTL's exhaustive reciprocal
// test is not repeated on the netlist: that sqrt pass already sends every fp24 value through the
// divider as a divisor, and the gate-level model runs 15-20 times slower than the RTL.)
#include <gtest/gtest.h>

#include "Vfp_units_e7f16_net.h"
#include "fp.hpp"
#include "fp_units_harness.hpp"

namespace rc::test {
namespace {

// A gate-level model simulates about 0.1 to 0.2 M cycles per second (the RTL model 1 to 2 M), so
// the random pairs are 10^6 here instead of the RTL's 10^7 (the exhaustive sqrt pass of
// `make test-long` adds 2^24 pairs with a scrambled second operand for the other units).
TEST(FpNetlist, Fp24SpecialAndRandom) {
  special_and_random<Vfp_units_e7f16_net, fp24>("netlist fp24", 1'000'000, 24);
}

}  // namespace
}  // namespace rc::test
