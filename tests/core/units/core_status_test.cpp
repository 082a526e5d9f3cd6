// rc_core_status's performance counters (rtl/core/rc_core_status.sv): each counter a word in block
// RAM that a sweep brings up to date from a small front counter, one counter per cycle.
//
// The contract, as a model: with S(e) the sum of a counter's increments sampled at edges <= e (the
// edges counted from the first after reset, 0), the counter's value before edge k is S(k - 2).
// The number sampled at edge k shows after edge k + 1 (two edges late) a word w with
// S(k - PerfSettle) <= w <= S(k - 2): it never runs ahead of the counter, and it is exact once
// PerfSettle edges have passed since the counter's last event. A number sampled at one of the
// first CorePerfCount + 2 edges after reset reads 0. The largest stack depth is exact: before edge
// k it is the largest perf_depth_i sampled with the stack-pushes field non-zero at edges <= k - 2.
// Numbers >= CorePerfCount read 0; built without per-kind counters (KindCounters = 0) the primary
// kind's counters read the totals of rays, traversal steps and triangle tests and the other kinds'
// read 0 whatever their increments. Seeded random increments (biased to large ones, so the fronts
// come near their limit), a depth that grows through the run and a random counter number at every
// edge (a quarter of them the largest depth's); then a quiet tail where every counter must read
// its exact total.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "Vcore_status_kind.h"
#include "Vcore_status_nokind.h"
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
void run(const char* what, bool kind_counters) {
  VerilatedTb<V> tb;
  std::mt19937 rng(kind_counters ? 0x5a7u : 0x5a8u);
  constexpr int kSettle = static_cast<int>(spec::kCorePerfSettleCycles);
  constexpr int kLatency = static_cast<int>(spec::kCorePerfReadLatency);
  static_assert(kLatency == 2, "the model below reads two edges late");

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
  tb.reset(1);  // an edge with rst_ni low (an asynchronous reset needs its edge in the model)

  // Every edge samples a number: random while busy; in the quiet tail, after PerfSettle edges,
  // 0, 1, .. 63 so that every number is read once the words are exact.
  static_assert(spec::kCorePerfCount <= 64, "the numbers read: 0 .. 63");
  const int busy = 4000, quiet = kSettle + 64 + kLatency;
  std::vector<int> sel_at;  // the number sampled at each edge
  uint64_t cases = 0, bad = 0, exact = 0;
  for (int e = 0; e < busy + quiet; ++e) {
    // The inputs sampled at edge e.
    std::array<uint32_t, kN> inc{};
    // A depth that grows through the run, so the largest one keeps changing while it is read.
    uint32_t depth = std::min(63u, static_cast<uint32_t>(e / 40 + static_cast<int>(rng() % 8u)));
    for (int k = 0; k < kN; ++k) {
      if (e < busy) inc[k] = (rng() % 4u == 0) ? rng() % 8u : 7u - rng() % 2u;
    }
    if (e >= busy) depth = 0;
    // (A quarter of the random numbers are the largest depth's, so its timing is seen often.)
    const int pick = rng() % 4u == 0 ? kMaxStack : static_cast<int>(rng() % 64u);
    const int sel = e < busy + kSettle ? pick : (e - busy - kSettle) % 64;
    sel_at.push_back(sel);
    clear(tb->perf_inc_i);
    for (int k = 0; k < kN; ++k) put_field(tb->perf_inc_i, 3 * k, 3, inc[k]);
    put(tb->perf_depth_i, depth);
    put(tb->perf_sel_i, static_cast<uint64_t>(sel));
    std::array<uint64_t, kN> next = sum.back();
    for (int k = 0; k < kN; ++k) next[k] += inc[k];
    sum.push_back(next);
    max_sp.push_back(inc[kPushes] != 0 ? std::max(max_sp.back(), depth) : max_sp.back());

    tb.tick();

    // After edge e: the number sampled at edge s = e - 1.
    const int s = e - (kLatency - 1);
    if (s < 0) continue;
    const int num = sel_at[static_cast<size_t>(s)];
    const auto at = [&](int edge, int k) -> uint64_t {
      return edge < 0 ? 0 : sum[static_cast<size_t>(edge) + 1][k];
    };
    // What number num reads: its own counter, or without per-kind counters a total (the primary
    // kind's) or nothing (the other kinds').
    int src = num;
    if (!kind_counters && kind_counter(num) >= 0) {
      const int64_t totals[3] = {spec::kCorePerfRays, spec::kCorePerfTraversalSteps,
                                 spec::kCorePerfTriangleTests};
      src = kind_counter(num) < 3 ? static_cast<int>(totals[kind_counter(num)]) : kN;
    }
    const uint64_t got = static_cast<uint64_t>(tb->perf_o);
    uint64_t lo = 0, hi = 0;  // the range the contract allows
    if (src >= kN || s < kN + 2) {
      lo = hi = 0;  // no such counter, or the words not yet written after reset
    } else if (src == kMaxStack) {
      lo = hi = max_sp[static_cast<size_t>(std::max(s - 1, 0))];  // edges <= s - 2
    } else {
      lo = at(s - kSettle, src);
      hi = at(s - 2, src);
      if (lo == hi) ++exact;
    }
    ++cases;
    if (got < lo || got > hi) {
      if (bad < 8)
        ADD_FAILURE() << what << ": number " << num << " sampled at edge " << s << " reads " << got
                      << ", want " << lo << " .. " << hi;
      ++bad;
    }
  }
  // The tail read every counter exact (at least the 20 that every build has), and the range was a
  // real bound while busy (the counters moved far beyond a front's reach).
  EXPECT_GE(exact, 20u) << what;
  EXPECT_GT(sum.back()[0], 5u * busy) << what;
  report_cases(what, cases, bad);
  EXPECT_EQ(bad, 0u) << what;
}

}  // namespace

TEST(CoreStatus, Counters) { run<Vcore_status_kind>("rc_core_status", true); }
TEST(CoreStatus, WithoutKindCountersThePrimaryOnesReadTheTotals) {
  run<Vcore_status_nokind>("rc_core_status KindCounters=0", false);
}

}  // namespace rc::test
