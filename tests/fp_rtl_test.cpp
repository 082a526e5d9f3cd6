// The verilated arithmetic units (rtl/fp/*) against the C++ model (tb/fp/fp.hpp), bit for bit.
//
// tests/rtl/rc_fp_units_tb.sv feeds one operand pair per cycle to the adder, multiplier, divider,
// square root and comparator in parallel; the harness (tests/fp_units_harness.hpp) checks every
// result and each pipeline's latency/valid behaviour. tests/fp_netlist_test.cpp runs the same
// tests on the synthesized netlist.
#include <gtest/gtest.h>

#include <cstdint>

#include "Vfp_units_e5f6.h"
#include "Vfp_units_e7f16.h"
#include "Vfp_units_e7f16_s1.h"
#include "Vfp_units_e8f23.h"
#include "fp.hpp"
#include "fp_units_harness.hpp"

namespace rc::test {
namespace {

TEST(FpRtl, ReducedFormatExhaustive) {
  using T = fp_reduced;
  UnitsHarness<Vfp_units_e5f6, T> h(1);
  const uint32_t n = 1u << T::kWidth;
  for (bool sub : {false, true})
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t j = 0; j < n; ++j) h.push(T::from_bits(i), T::from_bits(j), sub);
  finish(h,
         "rtl fp_reduced(1/5/6): all pairs, each as add and as sub (pairs, each through add|sub, "
         "mul, div, sqrt(a), cmp)");
}

TEST(FpRtl, ReducedFormatSqrtExhaustive) {
  sqrt_exhaustive<Vfp_units_e5f6, fp_reduced>("rtl fp_reduced(1/5/6)", 5);
}

TEST(FpRtl, Fp24SpecialAndRandom) {
  special_and_random<Vfp_units_e7f16, fp24>("rtl fp24", 10'000'000, 24);
}

// Every fp24 value as divisor of 1.0: the reciprocal, exhaustively.
TEST(FpRtl, Fp24ReciprocalExhaustive) {
  reciprocal_exhaustive<Vfp_units_e7f16, fp24>("rtl fp24", 2);
}

// Every fp24 bit pattern through the square root.
TEST(FpRtl, Fp24SqrtExhaustive) { sqrt_exhaustive<Vfp_units_e7f16, fp24>("rtl fp24", 3); }

TEST(FpRtl, Fp24OneStagePipelines) {
  special_and_random<Vfp_units_e7f16_s1, fp24>("rtl fp24 with Stages=1", 1'000'000, 241);
}

TEST(FpRtl, Fp32SpecialAndRandom) {
  special_and_random<Vfp_units_e8f23, fp32ftz>("rtl fp32ftz(1/8/23)", 2'000'000, 32);
}

TEST(FpRtl, Fp32SqrtSpecialAndRandom) {
  sqrt_special_and_random<Vfp_units_e8f23, fp32ftz>("rtl fp32ftz(1/8/23)", 3'000'000, 33);
}

}  // namespace
}  // namespace rc::test
