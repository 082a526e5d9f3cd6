// The synthesized netlist's exhaustive pass (tests/fp_netlist_test.cpp says what the netlist is):
// sqrt(x) for every fp24 x, with a second operand y that runs through every value too, in a
// scrambled order, for the other four units (the divider sees every divisor). 2^24 cycles of a
// gate-level model take 3 to 5 minutes of CPU, so this test carries the ctest label `long`:
// `make test-long` runs it, `make test` (and CI) does not. The RTL's own exhaustive pass
// (FpRtl.Fp24SqrtExhaustive) is in `make test`.
#include <gtest/gtest.h>

#include "Vfp_units_e7f16_net.h"
#include "fp.hpp"
#include "fp_units_harness.hpp"

namespace rc::test {
namespace {

TEST(FpNetlist, Fp24SqrtExhaustive) {
  sqrt_exhaustive<Vfp_units_e7f16_net, fp24>("netlist fp24", 3);
}

}  // namespace
}  // namespace rc::test
