// rc_core_status's performance counters (rtl/core/rc_core_status.sv): each counter is two halves
// with the low half's carry registered, so its high bits follow a cycle after its low bits.
// Verilated with the low half at 4 bits (the carry into the high half every few cycles) and at the
// core's 32 (where a frame never carries, so the split is exercised only by the small one).
//
// The contract, as a model: with S(e) the sum of a counter's increments sampled at edges <= e,
// after edge k the counter holds floor(S(k-2) / 2^L) * 2^L + (S(k-1) mod 2^L) (L = PerfLoW), so
// it is exact from the second edge after the last event; the largest stack depth holds the
// largest perf_depth_i sampled with the stack-pushes field non-zero at edges <= k-1; numbers >=
// CorePerfCount read 0; built without per-kind counters (KindCounters = 0) the primary kind's
// counters read the totals of rays, traversal steps and triangle tests and the other kinds' read 0
// whatever their increments. The read is a cycle late: perf_o after edge k shows the counter
// perf_sel_i named at edge k, as it was after edge k-1. Seeded random increments (biased to large
// ones so the small low half wraps often) and a random counter number at every edge; then a
// quiet tail where every counter must read its exact total.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "Vcore_status_lo32.h"
#include "Vcore_status_lo4.h"
#include "Vcore_status_lo4_nokind.h"
#include "fp_cases.hpp"
#include "rc_constants.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::clear;
using rc::harness::put;
using rc::harness::put_field;
using rc::harness::VerilatedTb;
namespace {

constexpr int kN = static_cast<int>(spec::kCorePerfCount);
constexpr int kMaxStack = static_cast<int>(spec::kCorePerfMaxStack);
constexpr int kPushes = static_cast<int>(spec::kCorePerfStackPushes);

// A per-kind counter number: -1 for another counter.
int kind_counter(int k) {
  const int lo = static_cast<int>(spec::kCorePerfPrimaryRays);
  return k >= lo && k < lo + 12 ? k - lo : -1;
}

template <class V>
void run(int low_bits, const char* what, bool kind_counters = true) {
  VerilatedTb<V> tb;
  std::mt19937 rng(0x5a7u + static_cast<uint32_t>(low_bits));
  const uint64_t low_mod = uint64_t{1} << low_bits;

  // S[e][k]: counter k's sum over the edges <= e (index e + 1; S[0] before any edge).
  std::vector<std::array<uint64_t, kN>> sum(1);
  sum[0].fill(0);
  std::vector<uint32_t> max_sp(1, 0);  // the largest depth over the edges <= e (index e + 1)

  tb->idle_i = 1;
  tb->wd_ev_i = 0;
  tb->err_i = 0;
  tb->perf_depth_i = 0;
  tb->perf_sel_i = 0;
  clear(tb->perf_inc_i);
  tb.reset(0);

  // The read is a cycle late: the number sampled at edge e shows, after edge e, the counter as it
  // was after edge e - 1. So every edge samples a number (random while busy; in the quiet tail
  // 0, 1, .. 31, 0, .. so that every number is read once the counters are exact).
  static_assert(spec::kCorePerfCount <= 64, "the numbers read: 0 .. 63");
  const int busy = 3000, quiet = 70;
  uint64_t cases = 0, bad = 0;
  for (int e = 0; e < busy + quiet; ++e) {
    // The inputs sampled at edge e.
    std::array<uint32_t, kN> inc{};
    uint32_t depth = rng() % 64u;
    for (int k = 0; k < kN; ++k) {
      if (e < busy) inc[k] = (rng() % 4u == 0) ? rng() % 8u : 7u - rng() % 2u;
    }
    if (e >= busy) depth = 0;
    const int sel = e < busy ? static_cast<int>(rng() % 64u) : (e - busy) % 64;
    clear(tb->perf_inc_i);
    for (int k = 0; k < kN; ++k) put_field(tb->perf_inc_i, 3 * k, 3, inc[k]);
    put(tb->perf_depth_i, depth);
    put(tb->perf_sel_i, static_cast<uint64_t>(sel));
    std::array<uint64_t, kN> next = sum.back();
    for (int k = 0; k < kN; ++k) next[k] += inc[k];
    sum.push_back(next);
    max_sp.push_back(inc[kPushes] != 0 ? std::max(max_sp.back(), depth) : max_sp.back());

    tb.tick();

    // After edge e: counter sel as it read after edge r = e - 1.
    const int r = e - 1;
    const auto at = [&](int edge, int k) -> uint64_t {
      return edge < 0 ? 0 : sum[static_cast<size_t>(edge) + 1][k];
    };
    // What counter sel reads: itself, or without per-kind counters a total (the primary kind's)
    // or nothing (the other kinds').
    int src = sel;
    if (!kind_counters && kind_counter(sel) >= 0) {
      const int64_t totals[3] = {spec::kCorePerfRays, spec::kCorePerfTraversalSteps,
                                 spec::kCorePerfTriangleTests};
      src = kind_counter(sel) < 3 ? static_cast<int>(totals[kind_counter(sel)]) : kN;
    }
    uint64_t want = 0;
    if (src >= kN || r < 0) {
      want = 0;  // no such counter, or the counters as reset
    } else if (src == kMaxStack) {
      want = r >= 1 ? max_sp[static_cast<size_t>(r)] : 0;  // edges <= r - 1
    } else {
      want = (at(r - 2, src) / low_mod) * low_mod + at(r - 1, src) % low_mod;
    }
    if (r >= busy + 1 && src < kN && src != kMaxStack) {
      // Two edges after the last event the counter is exact.
      EXPECT_EQ(want, at(busy - 1, src)) << "model";
    }
    ++cases;
    if (static_cast<uint64_t>(tb->perf_o) != want) {
      if (bad < 8)
        ADD_FAILURE() << what << ": after edge " << e << " counter " << sel << " reads "
                      << static_cast<uint64_t>(tb->perf_o) << ", want " << want;
      ++bad;
    }
  }
  // The small low half wrapped: its carries were exercised.
  if (low_bits < 32) {
    EXPECT_GT(sum.back()[0], 64 * low_mod) << what;
  }
  report_cases(what, cases, bad);
  EXPECT_EQ(bad, 0u) << what;
}

TEST(CoreStatus, CountersLowHalf4) { run<Vcore_status_lo4>(4, "rc_core_status PerfLoW=4"); }
TEST(CoreStatus, CountersLowHalf32) { run<Vcore_status_lo32>(32, "rc_core_status PerfLoW=32"); }
TEST(CoreStatus, WithoutKindCountersThePrimaryOnesReadTheTotals) {
  run<Vcore_status_lo4_nokind>(4, "rc_core_status PerfLoW=4 KindCounters=0", false);
}

}  // namespace
}  // namespace rc::test
