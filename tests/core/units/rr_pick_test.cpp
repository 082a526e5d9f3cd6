// rc_rr_pick (rtl/core/rc_rr_pick.sv), the core's round-robin thread scheduler, in both of its
// structures.
//
// One pointer over all requesters (N <= 32, rc_rr_pick_flat), verilated at N = 16 (the 16-thread
// core), 5 (not a power of two) and 1, exhaustively: for every pointer value and every request
// vector, valid_o and idx_o against a plain scan (the first requester at or after the pointer,
// wrapping around); then seeded random takes, checking after each that the pointer moved to the
// taken index + 1 (mod N) by the choice it makes next; one take in eight has no request at all,
// which must return the pointer to 0, or (TakeNeedsChoice = 1, verilated at N = 16 as n16c)
// leave it where it was. grant_o (the choice one-hot) is checked against the same reference in
// every case.
//
// Groups of 16 with a candidate register each (N > 32), verilated at N = 128 (the core's default
// thread count) and 40 (two full groups and a third padded with 8 requesters that never ask),
// against GroupedRef, a model written from the contract: per group a candidate (or none) and a
// pointer, and a pointer over the groups; the choice is the candidate of the first group holding
// one at or after the group pointer; at a clock edge a group with no candidate, or whose candidate
// is taken, loads the first of its requests at or after its pointer, leaving out the candidate it
// replaces and the requester taken in the cycle before (its pointer then moves past it, or to 0
// when there is none); a take moves the group pointer past the chosen group, or to 0 without a
// choice (with TakeNeedsChoice = 1, verilated at N = 64 as n64c, the board's thread count, a take
// without a choice changes nothing; n64c also has RegValid, valid_o from a flip-flop, which must
// give the same values every cycle). The requests keep the contract's rules: a requester asks until
// it is taken and drops at the take's edge or at the next one (drawn at random), and may ask again
// from the cycle after. Checked every cycle (valid_o, grant_o, and idx_o when valid_o is high):
// - seeded random: 240,000 cycles in runs of 1..400 cycles, each run one kind of arrivals (dense,
//   half, sparse, a few, a single requester, all requesters, the last group only (the padded one
//   at 40), one group, one requester in each of some groups, none), taken with probability 1, 3/4
//   or 1/4; every requester must be taken at least once, some takes have no choice, and the
//   assertions in the RTL (a candidate still asks) run throughout;
// - fairness: fixed sets of requesters that ask again as soon as the rules let them (all, dense,
//   sparse, one per group, a single one, the last group, a full group and one in every other
//   group), 30 N takes each (one cycle in eight without a take) after random traffic that
//   scatters the pointers; each served requester's wait (takes while it asked, the serving take
//   included) must be at most the contract's bound G (16 + 1) (136 at N = 128, 51 at N = 40);
//   the worst wait is printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "Vrr_pick_n1.h"
#include "Vrr_pick_n128.h"
#include "Vrr_pick_n16.h"
#include "Vrr_pick_n16c.h"
#include "Vrr_pick_n40.h"
#include "Vrr_pick_n5.h"
#include "Vrr_pick_n64c.h"
#include "fp_cases.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::clear;
using rc::harness::get_field;
using rc::harness::put;
using rc::harness::put_field;
using rc::harness::VerilatedTb;
namespace {

// The reference: the first set bit of req at or after ptr, wrapping; -1 when req is 0.
int first_from(uint32_t req, int ptr, int n) {
  for (int i = 0; i < n; ++i) {
    const int j = (ptr + i) % n;
    if ((req >> j) & 1u) return j;
  }
  return -1;
}

template <class V>
class Picker {
 public:
  explicit Picker(int n) : n_(n) {
    tb_->req_i = 0;
    tb_->take_i = 0;
    tb_.reset(2);
    for (int i = 0; i < 4; ++i) tb_.tick();
  }

  // The choice for req with no take (combinational): the index, or -1 when valid_o is 0.
  int choose(uint32_t req) {
    put(tb_->req_i, req);
    tb_->take_i = 0;
    tb_.eval();
    grant_ = static_cast<uint32_t>(tb_->grant_o);
    return tb_->valid_o ? static_cast<int>(tb_->idx_o) : -1;
  }
  // grant_o at the last choice.
  uint32_t grant() const { return grant_; }
  // Take the current choice for req; returns it (-1 with no request).
  int take(uint32_t req) {
    const int got = choose(req);
    tb_->take_i = 1;
    tb_.eval();
    tb_.tick();
    tb_->take_i = 0;
    tb_->req_i = 0;
    tb_.eval();
    return got;
  }
  // Move the pointer to p: take requester (p - 1) mod N alone.
  void set_ptr(int p) { take(1u << ((p + n_ - 1) % n_)); }

 private:
  int n_;
  uint32_t grant_ = 0;
  VerilatedTb<V> tb_;
};

template <class V>
void run(int n, const char* what, bool needs_choice = false) {
  Picker<V> pk(n);
  uint64_t cases = 0, bad = 0;
  const uint32_t all = n >= 32 ? 0xffffffffu : (1u << n) - 1u;
  for (int p = 0; p < n; ++p) {
    pk.set_ptr(p);
    for (uint32_t req = 0; req <= all; ++req) {
      const int want = first_from(req, p, n);
      const int got = pk.choose(req);
      const uint32_t want_grant = want < 0 ? 0u : 1u << want;
      ++cases;
      if (got != want || pk.grant() != want_grant) {
        if (bad < 8)
          ADD_FAILURE() << what << ": ptr " << p << " req 0x" << std::hex << req << std::dec
                        << ": idx " << got << ", want " << want << ", grant 0x" << std::hex
                        << pk.grant() << std::dec;
        ++bad;
      }
      if (req == all) break;
    }
  }
  // Random takes: the pointer follows the taken index, observed through the next choice with all
  // requesters asking (which must then be taken index + 1 mod N; after a take without a request
  // 0, or the pointer as it was with TakeNeedsChoice).
  std::mt19937 rng(0x5eed0000u + static_cast<uint32_t>(n));
  int ptr = 0;
  pk.set_ptr(0);
  for (int k = 0; k < 20000; ++k) {
    const uint32_t r = static_cast<uint32_t>(rng());
    const bool none = (r >> 29) == 0u;
    const uint32_t req =
        none ? 0u : (r & all) | (1u << (static_cast<uint32_t>(rng()) % static_cast<uint32_t>(n)));
    const int want = first_from(req, ptr, n);
    const int got = pk.take(req);
    ++cases;
    if (got != want) {
      if (bad < 8) ADD_FAILURE() << what << ": take " << k << ": idx " << got << ", want " << want;
      ++bad;
    }
    if (!none) {
      ptr = (want + 1) % n;
    } else if (!needs_choice) {
      ptr = 0;
    }
    ++cases;
    if (pk.choose(all) != ptr) {
      if (bad < 8) ADD_FAILURE() << what << ": take " << k << ": pointer not at " << ptr;
      ++bad;
    }
  }
  report_cases(what, cases, bad);
  EXPECT_EQ(bad, 0u);
}

TEST(RrPick, N16Exhaustive) {
  run<Vrr_pick_n16>(16, "rc_rr_pick N=16 (every pointer, every request)");
}
TEST(RrPick, N5Exhaustive) { run<Vrr_pick_n5>(5, "rc_rr_pick N=5 (every pointer, every request)"); }
TEST(RrPick, N1Exhaustive) { run<Vrr_pick_n1>(1, "rc_rr_pick N=1 (every pointer, every request)"); }
TEST(RrPick, N16TakeNeedsChoiceExhaustive) {
  run<Vrr_pick_n16c>(16, "rc_rr_pick N=16 TakeNeedsChoice (every pointer, every request)", true);
}

// ---- The grouped picker (N > 32) ----

constexpr int kGroup = 16;  // requesters per group (the contract)
constexpr int kMaxN = 128;

// A request or grant vector of up to kMaxN bits.
struct Bits {
  std::array<uint32_t, kMaxN / 32> w{};

  static std::size_t word(int i) { return static_cast<std::size_t>(i / 32); }
  bool test(int i) const { return ((w[word(i)] >> (i % 32)) & 1u) != 0u; }
  void set(int i) { w[word(i)] |= 1u << (i % 32); }
  void clear(int i) { w[word(i)] &= ~(1u << (i % 32)); }
  bool any() const { return w[0] != 0u || w[1] != 0u || w[2] != 0u || w[3] != 0u; }
  bool operator==(const Bits& o) const { return w == o.w; }
  bool operator!=(const Bits& o) const { return w != o.w; }
  static Bits one(int i) {
    Bits b;
    b.set(i);
    return b;
  }
  // Requesters lo .. hi-1.
  static Bits range(int lo, int hi) {
    Bits b;
    for (int i = lo; i < hi; ++i) b.set(i);
    return b;
  }
};

std::ostream& operator<<(std::ostream& os, const Bits& b) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "0x%08x_%08x_%08x_%08x", b.w[3], b.w[2], b.w[1], b.w[0]);
  return os << buf;
}

// The verilated ports (N > 32): up to 64 bits a QData, wider a VlWide of 32-bit words; either
// holds sizeof / 4 words.
template <class Port>
void put_bits(Port& port, const Bits& b) {
  static_assert(sizeof(Port) <= sizeof(b.w), "port wider than Bits");
  for (std::size_t i = 0; i < sizeof(Port) / 4; ++i)
    put_field(port, static_cast<int>(32 * i), 32, b.w[i]);
}
template <class Port>
Bits get_bits(const Port& port) {
  static_assert(sizeof(Port) <= sizeof(Bits::w), "port wider than Bits");
  Bits b;
  for (std::size_t i = 0; i < sizeof(Port) / 4; ++i)
    b.w[i] = static_cast<uint32_t>(get_field(port, static_cast<int>(32 * i), 32));
  return b;
}

// The reference for N > 32, from rc_rr_pick's contract: requesters in groups of 16 (the last
// padded with requesters that never ask), a candidate and a round-robin pointer in each group, a
// pointer over the groups holding a candidate. All pointers start at 0, no candidates.
class GroupedRef {
 public:
  GroupedRef(int n, bool needs_choice)
      : n_(n),
        needs_choice_(needs_choice),
        groups_((n + kGroup - 1) / kGroup),
        gptr_(static_cast<std::size_t>(groups_), 0),
        cand_(static_cast<std::size_t>(groups_), -1) {}

  int groups() const { return groups_; }
  int outer_ptr() const { return optr_; }
  int group_ptr(int g) const { return gptr_[static_cast<std::size_t>(g)]; }
  int cand(int g) const { return cand_[static_cast<std::size_t>(g)]; }

  // The choice, -1 without one: the candidate of the first group holding one at or after the
  // group pointer (wrapping around). It depends on the registers only.
  int choose() const {
    for (int k = 0; k < groups_; ++k) {
      const int g = (optr_ + k) % groups_;
      if (cand(g) >= 0) return cand(g);
    }
    return -1;
  }
  // The clock edge, with this cycle's requests and take.
  void edge(const Bits& req, bool take) {
    const int c = choose();
    const int cg = c < 0 ? -1 : c / kGroup;
    if (take && (c >= 0 || !needs_choice_)) optr_ = c < 0 ? 0 : (cg + 1) % groups_;
    for (int g = 0; g < groups_; ++g) {
      if (cand(g) >= 0 && !(take && g == cg)) continue;
      int pick = -1;
      for (int j = 0; j < kGroup && pick < 0; ++j) {
        const int i = g * kGroup + (group_ptr(g) + j) % kGroup;
        if (i < n_ && req.test(i) && i != cand(g) && i != taken_) pick = i;
      }
      cand_[static_cast<std::size_t>(g)] = pick;
      gptr_[static_cast<std::size_t>(g)] = pick < 0 ? 0 : (pick % kGroup + 1) % kGroup;
    }
    taken_ = take ? c : -1;
  }

 private:
  int n_;
  bool needs_choice_;
  int groups_;
  int optr_ = 0, taken_ = -1;
  std::vector<int> gptr_, cand_;
};

// The verilated grouped picker with the model beside it, compared every cycle.
template <class V>
class Checked {
 public:
  Checked(int n, const char* what, bool needs_choice) : n_(n), what_(what), ref_(n, needs_choice) {
    put_bits(tb_->req_i, Bits{});
    tb_->take_i = 0;
    tb_.reset(2);
    for (int i = 0; i < 4; ++i) tb_.tick();
  }

  int n() const { return n_; }
  uint64_t cases() const { return cases_; }
  uint64_t bad() const { return bad_; }
  // A failure found outside cycle() (counted with the mismatches).
  void fail(const std::string& why) {
    if (bad_ < 8) ADD_FAILURE() << what_ << ": cycle " << tb_.cycles() << ": " << why;
    ++bad_;
  }

  // One cycle: drive req_i and take_i, compare the choice with the model's, clock both. Returns
  // the picker's choice (-1 when valid_o is low).
  int cycle(const Bits& req, bool take) {
    const int want = ref_.choose();
    const Bits want_grant = want < 0 ? Bits{} : Bits::one(want);
    put_bits(tb_->req_i, req);
    tb_->take_i = static_cast<uint8_t>(take);
    tb_.eval();
    const bool valid = tb_->valid_o != 0;
    const int idx = static_cast<int>(tb_->idx_o);
    const Bits grant = get_bits(tb_->grant_o);
    ++cases_;
    if (valid != (want >= 0) || (valid && idx != want) || grant != want_grant) {
      if (bad_ < 8) {
        std::string ptrs = "group ptr " + std::to_string(ref_.outer_ptr()) + ", candidates";
        for (int g = 0; g < ref_.groups(); ++g)
          ptrs += " " + std::to_string(ref_.cand(g)) + "@" + std::to_string(ref_.group_ptr(g));
        ADD_FAILURE() << what_ << ": cycle " << tb_.cycles() << " (model " << ptrs << ") req "
                      << req << ": valid " << valid << " idx " << idx << " grant " << grant
                      << ", want " << (want >= 0) << " idx " << want << " grant " << want_grant;
      }
      ++bad_;
    }
    ref_.edge(req, take);
    tb_.tick();
    tb_->take_i = 0;
    return valid ? idx : -1;
  }

 private:
  int n_;
  const char* what_;
  GroupedRef ref_;
  uint64_t cases_ = 0, bad_ = 0;
  VerilatedTb<V> tb_;
};

// Request vectors over n requesters from a seeded generator.
class ReqGen {
 public:
  ReqGen(int n, uint32_t seed) : n_(n), groups_((n + kGroup - 1) / kGroup), rng_(seed) {}

  uint32_t below(uint32_t k) { return static_cast<uint32_t>(rng_()) % k; }
  int pick(int k) { return static_cast<int>(below(static_cast<uint32_t>(k))); }
  // Each requester with probability num / den.
  Bits density(uint32_t num, uint32_t den) {
    Bits b;
    for (int i = 0; i < n_; ++i)
      if (below(den) < num) b.set(i);
    return b;
  }
  Bits single() { return Bits::one(pick(n_)); }
  Bits few() {
    Bits b;
    for (int k = 1 + pick(3); k > 0; --k) b.set(pick(n_));
    return b;
  }
  // A non-empty random subset of requesters lo .. hi-1.
  Bits subset(int lo, int hi) {
    Bits b;
    for (int i = lo; i < hi; ++i)
      if (below(2) != 0u) b.set(i);
    b.set(lo + pick(hi - lo));
    return b;
  }
  Bits last_group() { return subset((groups_ - 1) * kGroup, n_); }
  Bits one_group() {
    const int g = pick(groups_);
    return subset(g * kGroup, std::min(n_, (g + 1) * kGroup));
  }
  // One requester in each of a random non-empty set of groups.
  Bits per_group() {
    Bits b;
    const int must = pick(groups_);
    for (int g = 0; g < groups_; ++g) {
      if (g != must && below(2) == 0u) continue;
      const int lo = g * kGroup, hi = std::min(n_, (g + 1) * kGroup);
      b.set(lo + pick(hi - lo));
    }
    return b;
  }

 private:
  int n_, groups_;
  std::mt19937 rng_;
};

enum Kind {
  kDense,
  kHalf,
  kSparse,
  kFew,
  kSingle,
  kAll,
  kLastGroup,
  kOneGroup,
  kPerGroup,
  kNone,
  kKinds
};

// New requests offered in one cycle (only requesters free to ask take them up).
Bits draw(ReqGen& gen, Kind kind, int n) {
  switch (kind) {
    case kDense: return gen.density(gen.below(2) != 0u ? 6 : 7, 8);
    case kHalf: return gen.density(1, 2);
    case kSparse: return gen.density(1, 32);
    case kFew: return gen.few();
    case kSingle: return gen.single();
    case kAll: return Bits::range(0, n);
    case kLastGroup: return gen.last_group();
    case kOneGroup: return gen.one_group();
    case kPerGroup: return gen.per_group();
    case kNone: return Bits{};
    case kKinds: break;
  }
  return Bits{};
}

// The requesters, kept to the contract's rules: a request stays up until it is taken, drops at
// the take's edge (late = false) or at the next one (late = true), and may rise again from the
// cycle after it dropped.
class Requests {
 public:
  explicit Requests(int n) : n_(n) {}
  const Bits& now() const { return req_; }
  // Requesters in `want` that are free to ask start asking (from this cycle).
  void ask(const Bits& want) {
    for (int i = 0; i < n_; ++i)
      if (want.test(i) && !blocked_.test(i)) req_.set(i);
  }
  // The clock edge: `taken` (or -1) was taken in the cycle that ends; `late` keeps its request up
  // for one more cycle.
  void edge(int taken, bool late) {
    blocked_ = Bits{};
    if (late_ >= 0) {
      req_.clear(late_);
      blocked_.set(late_);
      late_ = -1;
    }
    if (taken < 0) return;
    if (late) {
      late_ = taken;
      blocked_.set(taken);
    } else {
      req_.clear(taken);
      blocked_.set(taken);
    }
  }

 private:
  int n_;
  int late_ = -1;
  Bits req_, blocked_;
};

template <class V>
void run_grouped_random(int n, const char* what, bool needs_choice = false) {
  constexpr uint64_t kCycles = 240000;
  Checked<V> ck(n, what, needs_choice);
  ReqGen gen(n, 0x9e0b0000u + static_cast<uint32_t>(n));
  Requests rq(n);
  std::vector<uint64_t> taken(static_cast<std::size_t>(n), 0);
  std::array<uint64_t, kKinds> kind_cycles{};
  uint64_t cycles = 0, takes = 0, empty_takes = 0, late_drops = 0;
  while (cycles < kCycles) {
    const Kind kind = static_cast<Kind>(gen.pick(kKinds));
    const int len = 1 + gen.pick(400);
    const uint32_t take_in_8 = std::array<uint32_t, 3>{8, 6, 2}[gen.below(3)];
    // Arrivals every cycle, or only in the run's first cycle.
    const bool once = gen.below(2) != 0u;
    for (int k = 0; k < len; ++k, ++cycles) {
      if (!once || k == 0) rq.ask(draw(gen, kind, n));
      const bool take = gen.below(8) < take_in_8;
      const int got = ck.cycle(rq.now(), take);
      ++kind_cycles[static_cast<std::size_t>(kind)];
      const bool late = gen.below(2) != 0u;
      rq.edge(take ? got : -1, late);
      if (!take) continue;
      ++takes;
      if (got < 0) {
        ++empty_takes;
        continue;
      }
      if (late) ++late_drops;
      ++taken[static_cast<std::size_t>(got)];
    }
  }
  int never = 0;
  for (int i = 0; i < n; ++i)
    if (taken[static_cast<std::size_t>(i)] == 0u) {
      if (never++ < 4) ck.fail("requester " + std::to_string(i) + " never taken");
    }
  if (empty_takes == 0u) ck.fail("no take without a choice");
  if (late_drops == 0u) ck.fail("no request dropped a cycle after its take");
  for (int k = 0; k < kKinds; ++k)
    if (kind_cycles[static_cast<std::size_t>(k)] == 0u)
      ck.fail("request kind " + std::to_string(k) + " never drawn");
  const std::string line = std::string(what) + ": " + std::to_string(cycles) + " cycles, " +
                           std::to_string(takes) + " takes (" + std::to_string(empty_takes) +
                           " without a choice, " + std::to_string(late_drops) +
                           " requests dropped a cycle late), " +
                           (never == 0 ? std::string("every requester taken")
                                       : std::to_string(never) + " requesters never taken");
  report_cases(line.c_str(), ck.cases(), ck.bad());
  EXPECT_EQ(ck.bad(), 0u);
}

// Fairness: fixed sets of requesters that ask again as soon as they may; each must be served
// within the contract's bound of takes while it asks.
template <class V>
void run_grouped_fairness(int n, const char* what, bool needs_choice = false) {
  Checked<V> ck(n, what, needs_choice);
  ReqGen gen(n, 0xfa170000u + static_cast<uint32_t>(n));
  const int groups = (n + kGroup - 1) / kGroup;
  std::vector<std::pair<std::string, Bits>> sets;
  sets.emplace_back("all", Bits::range(0, n));
  sets.emplace_back("dense", gen.density(3, 4));
  Bits sparse = gen.density(1, 8);
  sparse.set(gen.pick(n));
  sets.emplace_back("sparse", sparse);
  Bits per_group;
  for (int g = 0; g < groups; ++g) {
    const int lo = g * kGroup, hi = std::min(n, (g + 1) * kGroup);
    per_group.set(lo + gen.pick(hi - lo));
  }
  sets.emplace_back("one per group", per_group);
  sets.emplace_back("single", gen.single());
  sets.emplace_back("last group", Bits::range((groups - 1) * kGroup, n));
  Bits full_and_ones = Bits::range(0, kGroup);
  for (int g = 1; g < groups; ++g)
    full_and_ones.set(g * kGroup + gen.pick(std::min(n - g * kGroup, kGroup)));
  sets.emplace_back("group 0 full + one per other group", full_and_ones);

  const int bound = groups * (kGroup + 1);  // the contract: G (16 + 1)
  const int takes_per_set = 30 * n;
  int worst = 0, over = 0;
  std::string worst_set, per_set;
  Requests rq(n);
  // Take every request that is up until none is left (no new ones).
  auto drain = [&] {
    for (int k = 0; k < 8 * n && rq.now().any(); ++k) rq.edge(ck.cycle(rq.now(), true), false);
    if (rq.now().any()) ck.fail("requests left after draining");
    for (int k = 0; k < 3; ++k) rq.edge(ck.cycle(rq.now(), true), false);
  };
  for (const auto& [name, set] : sets) {
    // Scatter the pointers with random traffic first, then let it drain.
    for (int k = 0; k < 500; ++k) {
      rq.ask(gen.density(1, 4));
      const bool take = gen.below(4) != 0u;
      const int got = ck.cycle(rq.now(), take);
      rq.edge(take ? got : -1, gen.below(2) != 0u);
    }
    drain();
    std::vector<int> pending(static_cast<std::size_t>(n), 0);
    int set_worst = 0;
    for (int takes = 0; takes < takes_per_set;) {
      rq.ask(set);
      const Bits asking = rq.now();
      const bool take = gen.below(8) != 0u;
      const bool late = gen.below(2) != 0u;
      const int got = ck.cycle(asking, take);
      rq.edge(take ? got : -1, late);
      if (!take) continue;
      ++takes;
      if (got < 0) continue;  // every asker is between its drop and its next candidacy
      if (!set.test(got)) {
        ck.fail(name + ": take " + std::to_string(takes) + " chose " + std::to_string(got));
        continue;
      }
      for (int i = 0; i < n; ++i)
        if (asking.test(i)) ++pending[static_cast<std::size_t>(i)];
      const int wait = pending[static_cast<std::size_t>(got)];
      pending[static_cast<std::size_t>(got)] = 0;
      set_worst = std::max(set_worst, wait);
      if (wait > bound) {
        ++over;
        ck.fail(name + ": requester " + std::to_string(got) + " served after " +
                std::to_string(wait) + " takes (more than " + std::to_string(bound) + ")");
      }
    }
    // Anyone still waiting at the end must not have waited longer either.
    for (int i = 0; i < n; ++i) {
      const int wait = pending[static_cast<std::size_t>(i)];
      if (!set.test(i) || wait <= bound) continue;
      set_worst = std::max(set_worst, wait);
      ++over;
      ck.fail(name + ": requester " + std::to_string(i) + " still waiting after " +
              std::to_string(wait) + " takes");
    }
    drain();
    if (set_worst > worst) {
      worst = set_worst;
      worst_set = name;
    }
    per_set += (per_set.empty() ? "" : ", ") + name + " " + std::to_string(set_worst);
  }
  const std::string line = std::string(what) + " (" + std::to_string(sets.size()) + " sets x " +
                           std::to_string(takes_per_set) + " takes; worst wait " +
                           std::to_string(worst) + " takes (" + worst_set + "), bound " +
                           std::to_string(bound) + ", " + std::to_string(over) +
                           " waits over it; " + per_set + ")";
  report_cases(line.c_str(), ck.cases(), ck.bad());
  EXPECT_EQ(ck.bad(), 0u);
}

TEST(RrPick, N128GroupedRandom) {
  run_grouped_random<Vrr_pick_n128>(128, "rc_rr_pick N=128 grouped (random vs the model)");
}
TEST(RrPick, N40GroupedRandom) {
  run_grouped_random<Vrr_pick_n40>(40, "rc_rr_pick N=40 grouped (random vs the model)");
}
TEST(RrPick, N128GroupedFairness) {
  run_grouped_fairness<Vrr_pick_n128>(128, "rc_rr_pick N=128 grouped fairness");
}
TEST(RrPick, N40GroupedFairness) {
  run_grouped_fairness<Vrr_pick_n40>(40, "rc_rr_pick N=40 grouped fairness");
}
TEST(RrPick, N64TakeNeedsChoiceGroupedRandom) {
  run_grouped_random<Vrr_pick_n64c>(
      64, "rc_rr_pick N=64 TakeNeedsChoice grouped (random vs the model)", true);
}
TEST(RrPick, N64TakeNeedsChoiceGroupedFairness) {
  run_grouped_fairness<Vrr_pick_n64c>(64, "rc_rr_pick N=64 TakeNeedsChoice grouped fairness", true);
}

}  // namespace
}  // namespace rc::test
