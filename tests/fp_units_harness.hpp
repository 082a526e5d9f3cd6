// The harness of the arithmetic unit tests: one verilated rc_fp_units_tb (the RTL at some format
// and pipeline depths, or its synthesized netlist) against the C++ model (tb/fp/fp.hpp), bit for
// bit. Used by tests/fp_rtl_test.cpp and tests/fp_netlist_test.cpp.
//
// tests/rtl/rc_fp_units_tb.sv feeds one operand pair per cycle to the adder, multiplier, divider,
// square root (of the first operand) and comparator in parallel. The harness keeps a queue of
// expected results per unit, inserts seeded random bubbles into valid_i, and checks every valid_o
// against the queue, so both the values and the latency/valid behaviour of each pipeline are
// checked.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "fp.hpp"
#include "fp_cases.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::put;
using rc::harness::VerilatedTb;

template <class V, class T>
class UnitsHarness {
 public:
  explicit UnitsHarness(uint64_t seed)
      : rng_(seed), start_(std::chrono::steady_clock::now()), cpu_start_(std::clock()) {
    tb_->valid_i = 0;
    tb_.reset(4, [this] { tick(); });
    tick();
  }
  UnitsHarness(const UnitsHarness&) = delete;
  UnitsHarness& operator=(const UnitsHarness&) = delete;

  // Applies one pair (after a random number of bubbles: one cycle in eight is idle).
  void push(T a, T b, bool sub) {
    while ((rng_() & 7) == 0) {
      tb_->valid_i = 0;
      tick();
    }
    tb_->valid_i = 1;
    tb_->sub_i = sub;
    // port width = the format's
    put(tb_->a_i, a.bits());
    put(tb_->b_i, b.bits());
    add_q_.push_back({a, b, sub ? (a - b).bits() : (a + b).bits(), sub ? 1u : 0u});
    mul_q_.push_back({a, b, (a * b).bits(), 0});
    div_q_.push_back({a, b, (a / b).bits(), 0});
    sqrt_q_.push_back({a, b, sqrt(a).bits(), 0});
    cmp_q_.push_back({a, b, 0, 0});
    tick();
    tb_->valid_i = 0;
    ++pairs_;
  }

  // Runs idle cycles until every pipeline has delivered everything; a stuck pipeline fails.
  void drain() {
    for (int i = 0; i < 1000 && !all_empty(); ++i) tick();
    EXPECT_TRUE(all_empty()) << "results still missing after 1000 idle cycles";
  }

  uint64_t pairs() const { return pairs_; }
  uint64_t mismatches() const { return mismatches_; }
  uint64_t cycles() const { return tb_.cycles(); }
  // Wall time and this process's CPU time since the harness was made (the CPU time is the
  // figure that holds on a loaded machine; the tests run single-threaded).
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  double cpu_seconds() const {
    return static_cast<double>(std::clock() - cpu_start_) / CLOCKS_PER_SEC;
  }

 private:
  struct Expect {
    T a, b;
    uint32_t res;
    uint32_t sub;
  };

  bool all_empty() const {
    return add_q_.empty() && mul_q_.empty() && div_q_.empty() && sqrt_q_.empty() && cmp_q_.empty();
  }

  void fail(const std::string& what) {
    if (++mismatches_ <= 10) ADD_FAILURE() << what;
  }

  // Pops the expectation for a unit whose valid_o is high; a valid_o with nothing expected is an
  // error (a spurious result).
  bool pop(std::deque<Expect>& q, const char* unit, Expect& e) {
    if (q.empty()) {
      fail(std::string(unit) + ": valid_o without a pending input");
      return false;
    }
    e = q.front();
    q.pop_front();
    return true;
  }

  std::string pair_text(const Expect& e) const { return "(" + e.a.hex() + ", " + e.b.hex() + ")"; }

  // The outputs are checked right after the rising edge.
  void tick() {
    tb_.tick([this] { check_outputs(); });
  }

  void check_outputs() {
    Expect e;
    if (tb_->add_valid_o && pop(add_q_, "add", e) && tb_->add_res_o != e.res)
      fail(std::string(e.sub ? "sub" : "add") + pair_text(e) + ": rtl " +
           T::from_bits(tb_->add_res_o).hex() + ", model " + T::from_bits(e.res).hex());
    if (tb_->mul_valid_o && pop(mul_q_, "mul", e) && tb_->mul_res_o != e.res)
      fail("mul" + pair_text(e) + ": rtl " + T::from_bits(tb_->mul_res_o).hex() + ", model " +
           T::from_bits(e.res).hex());
    if (tb_->div_valid_o && pop(div_q_, "div", e) && tb_->div_res_o != e.res)
      fail("div" + pair_text(e) + ": rtl " + T::from_bits(tb_->div_res_o).hex() + ", model " +
           T::from_bits(e.res).hex());
    if (tb_->sqrt_valid_o && pop(sqrt_q_, "sqrt", e) && tb_->sqrt_res_o != e.res)
      fail("sqrt(" + e.a.hex() + "): rtl " + T::from_bits(tb_->sqrt_res_o).hex() + ", model " +
           T::from_bits(e.res).hex());
    if (tb_->cmp_valid_o && pop(cmp_q_, "cmp", e)) {
      const bool want_lt = lt(e.a, e.b), want_le = le(e.a, e.b), want_eq = eq(e.a, e.b);
      const uint32_t want_min = min(e.a, e.b).bits(), want_max = max(e.a, e.b).bits();
      if (tb_->lt_o != want_lt || tb_->le_o != want_le || tb_->eq_o != want_eq)
        fail("cmp" + pair_text(e) + ": rtl lt/le/eq " + std::to_string(tb_->lt_o) +
             std::to_string(tb_->le_o) + std::to_string(tb_->eq_o) + ", model " +
             std::to_string(want_lt) + std::to_string(want_le) + std::to_string(want_eq));
      if (tb_->min_o != want_min || tb_->max_o != want_max)
        fail("min/max" + pair_text(e) + ": rtl " + T::from_bits(tb_->min_o).hex() + "/" +
             T::from_bits(tb_->max_o).hex() + ", model " + T::from_bits(want_min).hex() + "/" +
             T::from_bits(want_max).hex());
    }
  }

  VerilatedTb<V> tb_;
  std::mt19937_64 rng_;
  std::chrono::steady_clock::time_point start_;
  std::clock_t cpu_start_;
  std::deque<Expect> add_q_, mul_q_, div_q_, sqrt_q_, cmp_q_;
  uint64_t pairs_ = 0, mismatches_ = 0;
};

// Drains the pipelines, prints the [cases] line (what + the number of pairs pushed and the
// mismatches of every unit) and the simulation speed (from the harness's construction), and
// fails on any mismatch.
template <class V, class T>
void finish(UnitsHarness<V, T>& h, const std::string& what) {
  h.drain();
  report_cases(what.c_str(), h.pairs(), h.mismatches());
  const double wall = h.seconds(), cpu = h.cpu_seconds();
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  std::printf("[speed] %s.%s: %llu cycles in %.1f s (%.1f s CPU), %.2f M cycles per CPU second\n",
              test ? test->test_suite_name() : "?", test ? test->name() : "?",
              static_cast<unsigned long long>(h.cycles()), wall, cpu,
              cpu > 0.0 ? static_cast<double>(h.cycles()) / cpu * 1e-6 : 0.0);
  std::fflush(stdout);
  EXPECT_EQ(h.mismatches(), 0u);
}

// Special x special and random pairs, each pushed as add and as sub; every pair drives all five
// units (sqrt takes the first operand).
template <class V, class T>
void special_and_random(const std::string& label, uint64_t random_pairs, uint64_t seed) {
  UnitsHarness<V, T> h(seed);
  const auto sv = special_values<T>();
  for (bool sub : {false, true})
    for (T a : sv)
      for (T b : sv) h.push(a, b, sub);
  PairGen<T> gen(seed ^ 0x9e3779b97f4a7c15ull);
  T a, b;
  for (bool sub : {false, true})
    for (uint64_t i = 0; i < random_pairs; ++i) {
      gen.next(a, b);
      h.push(a, b, sub);
    }
  finish(h, label + ": special x special and " + std::to_string(random_pairs) +
                " random pairs, each as add and as sub (pairs, each through add|sub, mul, div, "
                "sqrt(a), cmp)");
}

// Every x through 1 / x (and the other units with the pair (1, x)): the reciprocal, exhaustively.
template <class V, class T>
void reciprocal_exhaustive(const std::string& label, uint64_t seed) {
  UnitsHarness<V, T> h(seed);
  const T one = T::one();
  for (uint32_t i = 0; i < (1u << T::kWidth); ++i) h.push(one, T::from_bits(i), false);
  finish(h, label +
                " reciprocal 1/x, every x (pairs (1, x), each through add, mul, div, sqrt, "
                "cmp)");
}

// A fixed permutation of the format's bit patterns that looks random (odd multiplications and
// xor-shifts, each a bijection of kWidth-bit values).
template <class T>
uint32_t scramble(uint32_t x) {
  constexpr int kHalf = T::kWidth / 2;
  x = (x * 0x9e3779b1u) & T::kMask;
  x ^= x >> kHalf;
  x = (x * 0x85ebca6bu) & T::kMask;
  return x ^ (x >> (kHalf + 1));
}

// Every x through sqrt(x). The second operand y = scramble(x) runs through every value as well,
// in a random-looking order, and add or sub is chosen at random: the other units see as many
// random pairs on the way, and the divider every divisor once.
template <class V, class T>
void sqrt_exhaustive(const std::string& label, uint64_t seed) {
  UnitsHarness<V, T> h(seed);
  std::mt19937_64 rng(seed ^ 0x243f6a8885a308d3ull);
  for (uint32_t i = 0; i < (1u << T::kWidth); ++i)
    h.push(T::from_bits(i), T::from_bits(scramble<T>(i)), (rng() >> 40) & 1);
  finish(h, label +
                " sqrt(x), every x (pairs (x, y), y a permutation of every value, each "
                "through add|sub, mul, div, sqrt, cmp)");
}

// sqrt of the special values, of random positive encodings, of exact squares k^2 * 4^s (whose
// root is exact, so the remainder is 0 and nothing rounds) and of their neighbours one ulp away
// (roots just beside a representable value). For formats too wide to test exhaustively.
template <class V, class T>
void sqrt_special_and_random(const std::string& label, uint64_t randoms, uint64_t seed) {
  UnitsHarness<V, T> h(seed);
  for (T a : special_values<T>()) h.push(a, a, false);
  std::mt19937_64 rng(seed ^ 0x5a5a5a5a5a5a5a5aull);
  // k^2 < 2^(F+1) is exact in the format; 4^s with |2 s| inside the exponent range.
  const uint64_t k_max = uint64_t{1} << ((T::kFracW + 1) / 2);
  const int s_max = (T::kBias - 1) / 2 - (T::kFracW + 1) / 2 - 1;
  for (uint64_t i = 0; i < randoms; ++i) {
    T a;
    if (i % 3 == 0) {
      a = T::from_bits(static_cast<uint32_t>(rng()) & ~T::kSignBit);
    } else {
      const uint64_t k = 1 + rng() % (k_max - 1);
      const int s = static_cast<int>(rng() % static_cast<uint64_t>(2 * s_max + 1)) - s_max;
      a = T::from_double(std::ldexp(static_cast<double>(k * k), 2 * s));
      if (i % 3 == 2) a = T::from_bits((rng() & 1) ? a.bits() + 1 : a.bits() - 1);
    }
    h.push(a, a, false);
  }
  finish(h, label + " sqrt: specials, " + std::to_string(randoms) +
                " random positive values, exact squares and their neighbours (pairs (x, x), each "
                "through add, mul, div, sqrt, cmp)");
}

}  // namespace rc::test
