// The verilated arithmetic units (rtl/fp/*) against the C++ model (tb/fp/fp.hpp), bit for bit.
//
// tests/rtl/rc_fp_units_tb.sv feeds one operand pair per cycle to the adder, multiplier, divider
// and comparator in parallel. The harness keeps a queue of expected results per unit, inserts
// seeded random bubbles into valid_i, and checks every valid_o against the queue, so both the
// values and the latency/valid behaviour of each pipeline are checked.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <type_traits>

#include "Vfp_units_e5f6.h"
#include "Vfp_units_e7f16.h"
#include "Vfp_units_e7f16_s1.h"
#include "Vfp_units_e8f23.h"
#include "fp.hpp"
#include "fp_cases.hpp"
#include "verilated.h"

namespace rc::test {
namespace {

template <class V, class T>
class UnitsHarness {
 public:
  explicit UnitsHarness(uint64_t seed) : ctx_(std::make_unique<VerilatedContext>()), rng_(seed) {
    ctx_->assertOn(true);
    dut_ = std::make_unique<V>(ctx_.get());
    dut_->clk_i = 0;
    dut_->rst_ni = 0;
    dut_->valid_i = 0;
    dut_->eval();
    for (int i = 0; i < 4; ++i) tick();
    dut_->rst_ni = 1;
    tick();
  }
  ~UnitsHarness() { dut_->final(); }

  // Applies one pair (after a random number of bubbles: one cycle in eight is idle).
  void push(T a, T b, bool sub) {
    while ((rng_() & 7) == 0) {
      dut_->valid_i = 0;
      tick();
    }
    dut_->valid_i = 1;
    dut_->sub_i = sub;
    dut_->a_i = static_cast<std::remove_reference_t<decltype(dut_->a_i)>>(a.bits());  // port width = the format's
    dut_->b_i = static_cast<std::remove_reference_t<decltype(dut_->b_i)>>(b.bits());
    add_q_.push_back({a, b, sub ? (a - b).bits() : (a + b).bits(), sub ? 1u : 0u});
    mul_q_.push_back({a, b, (a * b).bits(), 0});
    div_q_.push_back({a, b, (a / b).bits(), 0});
    cmp_q_.push_back({a, b, 0, 0});
    tick();
    dut_->valid_i = 0;
    ++pairs_;
  }

  // Runs idle cycles until every pipeline has delivered everything; a stuck pipeline fails.
  void drain() {
    for (int i = 0; i < 1000 && !(add_q_.empty() && mul_q_.empty() && div_q_.empty() &&
                                  cmp_q_.empty());
         ++i)
      tick();
    EXPECT_TRUE(add_q_.empty() && mul_q_.empty() && div_q_.empty() && cmp_q_.empty())
        << "results still missing after 1000 idle cycles";
  }

  uint64_t pairs() const { return pairs_; }
  uint64_t mismatches() const { return mismatches_; }

 private:
  struct Expect {
    T a, b;
    uint32_t res;
    uint32_t sub;
  };

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

  void tick() {
    dut_->clk_i = 1;
    dut_->eval();
    ctx_->timeInc(1);
    check_outputs();
    dut_->clk_i = 0;
    dut_->eval();
    ctx_->timeInc(1);
  }

  void check_outputs() {
    Expect e;
    if (dut_->add_valid_o && pop(add_q_, "add", e) && dut_->add_res_o != e.res)
      fail(std::string(e.sub ? "sub" : "add") + pair_text(e) + ": rtl " +
           T::from_bits(dut_->add_res_o).hex() + ", model " + T::from_bits(e.res).hex());
    if (dut_->mul_valid_o && pop(mul_q_, "mul", e) && dut_->mul_res_o != e.res)
      fail("mul" + pair_text(e) + ": rtl " + T::from_bits(dut_->mul_res_o).hex() + ", model " +
           T::from_bits(e.res).hex());
    if (dut_->div_valid_o && pop(div_q_, "div", e) && dut_->div_res_o != e.res)
      fail("div" + pair_text(e) + ": rtl " + T::from_bits(dut_->div_res_o).hex() + ", model " +
           T::from_bits(e.res).hex());
    if (dut_->cmp_valid_o && pop(cmp_q_, "cmp", e)) {
      const bool want_lt = lt(e.a, e.b), want_le = le(e.a, e.b), want_eq = eq(e.a, e.b);
      const uint32_t want_min = min(e.a, e.b).bits(), want_max = max(e.a, e.b).bits();
      if (dut_->lt_o != want_lt || dut_->le_o != want_le || dut_->eq_o != want_eq)
        fail("cmp" + pair_text(e) + ": rtl lt/le/eq " + std::to_string(dut_->lt_o) +
             std::to_string(dut_->le_o) + std::to_string(dut_->eq_o) + ", model " +
             std::to_string(want_lt) + std::to_string(want_le) + std::to_string(want_eq));
      if (dut_->min_o != want_min || dut_->max_o != want_max)
        fail("min/max" + pair_text(e) + ": rtl " + T::from_bits(dut_->min_o).hex() + "/" +
             T::from_bits(dut_->max_o).hex() + ", model " + T::from_bits(want_min).hex() + "/" +
             T::from_bits(want_max).hex());
    }
  }

  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<V> dut_;
  std::mt19937_64 rng_;
  std::deque<Expect> add_q_, mul_q_, div_q_, cmp_q_;
  uint64_t pairs_ = 0, mismatches_ = 0;
};

// Each pair drives all four units: add (or sub), mul, div and cmp (lt, le, eq, min, max).
template <class V, class T>
void finish(UnitsHarness<V, T>& h, const std::string& what) {
  h.drain();
  report_cases((what + " (pairs, each through add|sub, mul, div, cmp)").c_str(), h.pairs(),
               h.mismatches());
  EXPECT_EQ(h.mismatches(), 0u);
}

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
                " random pairs, each as add and as sub");
}

TEST(FpRtl, ReducedFormatExhaustive) {
  using T = fp_reduced;
  UnitsHarness<Vfp_units_e5f6, T> h(1);
  const uint32_t n = 1u << T::kWidth;
  for (bool sub : {false, true})
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t j = 0; j < n; ++j) h.push(T::from_bits(i), T::from_bits(j), sub);
  finish(h, "rtl fp_reduced(1/5/6): all pairs, each as add and as sub");
}

TEST(FpRtl, Fp24SpecialAndRandom) {
  special_and_random<Vfp_units_e7f16, fp24>("rtl fp24", 10'000'000, 24);
}

// Every fp24 value as divisor of 1.0: the reciprocal, exhaustively.
TEST(FpRtl, Fp24ReciprocalExhaustive) {
  using T = fp24;
  UnitsHarness<Vfp_units_e7f16, T> h(2);
  const T one = T::from_double(1.0);
  for (uint32_t i = 0; i < (1u << T::kWidth); ++i) h.push(one, T::from_bits(i), false);
  finish(h, "rtl fp24 reciprocal 1/x, every x");
}

TEST(FpRtl, Fp24OneStagePipelines) {
  special_and_random<Vfp_units_e7f16_s1, fp24>("rtl fp24 with Stages=1", 1'000'000, 241);
}

TEST(FpRtl, Fp32SpecialAndRandom) {
  special_and_random<Vfp_units_e8f23, fp32ftz>("rtl fp32ftz(1/8/23)", 2'000'000, 32);
}

}  // namespace
}  // namespace rc::test
