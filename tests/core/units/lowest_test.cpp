// rc_lowest (rtl/core/rc_lowest.sv): the lowest set bit of a vector, combinational, in groups of
// 16. Verilated at N = 1, 5 and 16 (one group: every vector, exhaustively), 40 (two full groups
// and a padded one), 64 (the tracer's slots) and 128 (its shadow packets).
//
// The contract says valid_o = any bit set, idx_o = the lowest set bit's index (0 when none) and
// hot_o = that bit alone (0 when none). The reference is a loop over the bits here. Beyond one
// group, every lowest position is checked with seeded random bits above it (64 vectors each),
// with all bits above it set and with it alone; and the empty and the full vector.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "Vlowest_n1.h"
#include "Vlowest_n128.h"
#include "Vlowest_n16.h"
#include "Vlowest_n40.h"
#include "Vlowest_n5.h"
#include "Vlowest_n64.h"
#include "fp_cases.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::get_field;
using rc::harness::put_bits;
using rc::harness::VerilatedTb;
namespace {

template <class V>
void run(int n, const char* what) {
  VerilatedTb<V> tb;
  std::mt19937 rng(0x10e5u + static_cast<uint32_t>(n));

  std::vector<std::vector<bool>> vectors;
  if (n <= 16) {
    for (uint32_t v = 0; v < (1u << n); ++v) {
      std::vector<bool> bits(static_cast<size_t>(n));
      for (int i = 0; i < n; ++i) bits[static_cast<size_t>(i)] = ((v >> i) & 1u) != 0;
      vectors.push_back(std::move(bits));
    }
  } else {
    vectors.emplace_back(static_cast<size_t>(n), false);
    vectors.emplace_back(static_cast<size_t>(n), true);
    for (int p = 0; p < n; ++p) {
      for (int k = 0; k < 66; ++k) {
        std::vector<bool> bits(static_cast<size_t>(n), false);
        bits[static_cast<size_t>(p)] = true;
        for (int i = p + 1; i < n; ++i)
          bits[static_cast<size_t>(i)] = k == 0 ? false : k == 1 ? true : (rng() & 1u) != 0;
        vectors.push_back(std::move(bits));
      }
    }
  }

  uint64_t cases = 0, bad = 0;
  for (const std::vector<bool>& bits : vectors) {
    int want = -1;
    for (int i = n - 1; i >= 0; --i)
      if (bits[static_cast<size_t>(i)]) want = i;
    put_bits(tb->req_i, bits);
    tb.eval();
    bool ok = static_cast<bool>(tb->valid_o) == (want >= 0) &&
              static_cast<int>(tb->idx_o) == (want >= 0 ? want : 0);
    for (int i = 0; i < n; ++i) ok = ok && (get_field(tb->hot_o, i, 1) != 0) == (i == want);
    ++cases;
    if (!ok) {
      if (bad < 8)
        ADD_FAILURE() << what << ": lowest set bit " << want << ", got valid " << int(tb->valid_o)
                      << " index " << int(tb->idx_o);
      ++bad;
    }
  }
  report_cases(what, cases, bad);
  EXPECT_EQ(bad, 0u) << what;
}

TEST(Lowest, N1Exhaustive) { run<Vlowest_n1>(1, "rc_lowest N=1"); }
TEST(Lowest, N5Exhaustive) { run<Vlowest_n5>(5, "rc_lowest N=5"); }
TEST(Lowest, N16Exhaustive) { run<Vlowest_n16>(16, "rc_lowest N=16"); }
TEST(Lowest, N40PaddedGroup) { run<Vlowest_n40>(40, "rc_lowest N=40"); }
TEST(Lowest, N64) { run<Vlowest_n64>(64, "rc_lowest N=64"); }
TEST(Lowest, N128) { run<Vlowest_n128>(128, "rc_lowest N=128"); }

}  // namespace
}  // namespace rc::test
