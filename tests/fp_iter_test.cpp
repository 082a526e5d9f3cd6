// The iterative divider and square root (rtl/fp/rc_fp_div_iter.sv, rtl/fp/rc_fp_sqrt_iter.sv)
// against the C++ model (tb/fp/fp.hpp), bit for bit and cycle for cycle.
//
// tests/rtl/rc_fp_iter_tb.sv gives each unit its own operand stream. The harness issues each
// stream's operations as close together as the unit's contract allows (operations i and
// i + Lanes at least Iters + 1 cycles apart: the tightest spacing, every lane reused as soon as it
// is free) or at random legal spacings, and checks every result against the model and every
// valid_o at exactly Stages cycles after its operation (a missing, late or spurious result fails).
// A stream that breaks the spacing must stop the simulation at the unit's assertion.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "Vfp_iter_e5f6_l1.h"
#include "Vfp_iter_e5f6_l2.h"
#include "Vfp_iter_e7f16_l1.h"
#include "Vfp_iter_e7f16_l2.h"
#include "Vfp_iter_e7f16_l2_s.h"
#include "fp.hpp"
#include "fp_cases.hpp"
#include "verilated_tb.hpp"

namespace rc::test {
namespace {

using rc::harness::put;
using rc::harness::TbError;
using rc::harness::VerilatedTb;

// How a stream's operations are spaced: as tight as the contract allows, or at random legal
// spacings (a free lane is used with probability 1/2 each cycle).
enum class Spacing { kTight, kRandom };

struct Op {
  uint32_t a, b;  // the square root reads a only
};

// The units' parameters as verilated (tests/CMakeLists.txt, fp_iter's configs).
struct Config {
  int lanes;
  int div_stages, sqrt_stages;
};

template <class V, class T>
class IterHarness {
 public:
  IterHarness(const Config& cfg, uint64_t seed, bool fatal_on_error = true)
      : tb_("TOP", fatal_on_error), rng_(seed), cfg_(cfg) {
    div_.interval = T::kFracW / 2 + 1;
    sqrt_.interval = (T::kFracW - 2) / 2 + 1;
    div_.stages = cfg.div_stages;
    sqrt_.stages = cfg.sqrt_stages;
    tb_->div_valid_i = 0;
    tb_->sqrt_valid_i = 0;
    tb_.reset(4);
  }

  // Runs both streams to the end (each spaced as asked; `gap` > 0 puts operation i + Lanes only
  // Interval - gap cycles after operation i, against the contract) and drains the units.
  void run(const std::vector<Op>& div_ops, const std::vector<Op>& sqrt_ops, Spacing spacing,
           int gap = 0) {
    size_t di = 0, si = 0;
    while (di < div_ops.size() || si < sqrt_ops.size() || !div_.q.empty() || !sqrt_.q.empty()) {
      tb_->div_valid_i = 0;
      tb_->sqrt_valid_i = 0;
      if (di < div_ops.size() && may_issue(div_, spacing, gap)) {
        const Op& op = div_ops[di++];
        tb_->div_valid_i = 1;
        put(tb_->a_i, op.a);
        put(tb_->b_i, op.b);
        issue(div_, op, (T::from_bits(op.a) / T::from_bits(op.b)).bits());
      }
      if (si < sqrt_ops.size() && may_issue(sqrt_, spacing, gap)) {
        const Op& op = sqrt_ops[si++];
        tb_->sqrt_valid_i = 1;
        put(tb_->s_i, op.a);
        issue(sqrt_, op, sqrt(T::from_bits(op.a)).bits());
      }
      tb_.tick([this] { check(); });
      if (tb_.cycles() > limit_) {
        ADD_FAILURE() << "results still missing at cycle " << tb_.cycles();
        return;
      }
    }
  }

  uint64_t ops() const { return div_.issued + sqrt_.issued; }
  uint64_t mismatches() const { return mismatches_; }
  uint64_t cycles() const { return tb_.cycles(); }

 private:
  struct Expect {
    Op op;
    uint32_t res;
    uint64_t due;  // the rising edge after which valid_o shows it
  };
  struct Stream {
    int interval = 1, stages = 1;
    std::deque<uint64_t> recent;  // the cycles of the last Lanes operations
    std::deque<Expect> q;
    uint64_t issued = 0;
  };

  // Rising edges are numbered from 1: the one about to come is tb_.cycles() + 1.
  bool may_issue(Stream& s, Spacing spacing, int gap) {
    const uint64_t now = tb_.cycles() + 1;
    const bool free = static_cast<int>(s.recent.size()) < cfg_.lanes ||
                      now - s.recent.front() >= static_cast<uint64_t>(s.interval - gap);
    return free && (spacing == Spacing::kTight || (rng_() & 1) != 0);
  }

  void issue(Stream& s, const Op& op, uint32_t res) {
    const uint64_t now = tb_.cycles() + 1;
    s.recent.push_back(now);
    if (static_cast<int>(s.recent.size()) > cfg_.lanes) s.recent.pop_front();
    s.q.push_back({op, res, now + static_cast<uint64_t>(s.stages) - 1});
    ++s.issued;
    limit_ = now + 1000;
  }

  void fail(const std::string& what) {
    if (++mismatches_ <= 10) ADD_FAILURE() << what << " (cycle " << tb_.cycles() << ")";
  }

  // One unit's output after the edge: valid_o exactly when an operation is due, with its result.
  void check_stream(Stream& s, const char* unit, bool valid, uint32_t res) {
    const uint64_t now = tb_.cycles() + 1;  // (counted once the edge's tick is over)
    const bool due = !s.q.empty() && s.q.front().due == now;
    if (valid != due) {
      fail(std::string(unit) + (valid ? ": valid_o with no operation due" : ": valid_o missing"));
      if (due) s.q.pop_front();
      return;
    }
    if (!valid) return;
    const Expect e = s.q.front();
    s.q.pop_front();
    if (res != e.res)
      fail(std::string(unit) + "(" + T::from_bits(e.op.a).hex() + ", " +
           T::from_bits(e.op.b).hex() + "): rtl " + T::from_bits(res).hex() + ", model " +
           T::from_bits(e.res).hex());
  }

  void check() {
    check_stream(div_, "div", tb_->div_valid_o, static_cast<uint32_t>(tb_->div_res_o));
    check_stream(sqrt_, "sqrt", tb_->sqrt_valid_o, static_cast<uint32_t>(tb_->sqrt_res_o));
  }

  VerilatedTb<V> tb_;
  std::mt19937_64 rng_;
  Config cfg_;
  Stream div_, sqrt_;
  uint64_t mismatches_ = 0, limit_ = 1000;
};

template <class V, class T>
void finish(IterHarness<V, T>& h, const std::string& what) {
  report_cases(what.c_str(), h.ops(), h.mismatches());
  std::printf("[speed] %llu cycles\n", static_cast<unsigned long long>(h.cycles()));
  std::fflush(stdout);
  EXPECT_EQ(h.mismatches(), 0u);
}

template <class T>
std::vector<Op> every_value() {
  std::vector<Op> ops;
  for (uint32_t i = 0; i < (1u << T::kWidth); ++i) ops.push_back({i, 0});
  return ops;
}

template <class T>
std::vector<Op> specials_and_random(uint64_t randoms, uint64_t seed) {
  std::vector<Op> ops;
  for (T a : special_values<T>())
    for (T b : special_values<T>()) ops.push_back({a.bits(), b.bits()});
  PairGen<T> gen(seed);
  T a, b;
  for (uint64_t i = 0; i < randoms; ++i) {
    gen.next(a, b);
    ops.push_back({a.bits(), b.bits()});
  }
  return ops;
}

constexpr Config kReduced1{1, 11, 10}, kReduced2{2, 11, 10};
constexpr Config kFp24L1{1, 11, 10}, kFp24L2{2, 11, 10}, kFp24L2Long{2, 13, 12};

// The reduced format: every pair through the divider, every value through the square root (as
// often as the divider's stream lasts), tight and at random spacings, with one lane and two.
template <class V>
void reduced_exhaustive(const Config& cfg, Spacing spacing, uint64_t seed) {
  using T = fp_reduced;
  IterHarness<V, T> h(cfg, seed);
  std::vector<Op> div_ops, sqrt_ops;
  const uint32_t n = 1u << T::kWidth;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = 0; j < n; ++j) div_ops.push_back({i, j});
  for (int rep = 0; rep < 64; ++rep)
    for (uint32_t i = 0; i < n; ++i) sqrt_ops.push_back({(i + static_cast<uint32_t>(rep)) % n, 0});
  h.run(div_ops, sqrt_ops, spacing);
  finish(h, "rtl iterative fp_reduced(1/5/6), " + std::to_string(cfg.lanes) + " lane(s), " +
                (spacing == Spacing::kTight ? "tightest" : "random") +
                " spacing: every pair a / b, every value 64 times through sqrt (operations)");
}

TEST(FpIterRtl, ReducedExhaustiveOneLaneTight) {
  reduced_exhaustive<Vfp_iter_e5f6_l1>(kReduced1, Spacing::kTight, 1);
}
TEST(FpIterRtl, ReducedExhaustiveTwoLanesTight) {
  reduced_exhaustive<Vfp_iter_e5f6_l2>(kReduced2, Spacing::kTight, 2);
}
TEST(FpIterRtl, ReducedExhaustiveTwoLanesRandom) {
  reduced_exhaustive<Vfp_iter_e5f6_l2>(kReduced2, Spacing::kRandom, 3);
}

// fp24 as the lit board uses the units (two lanes, tightest spacing): every x through 1 / x
// (the light units' and the ray generator's divisions) and through sqrt(x).
TEST(FpIterRtl, Fp24ReciprocalAndSqrtExhaustive) {
  using T = fp24;
  IterHarness<Vfp_iter_e7f16_l2, T> h(kFp24L2, 4);
  std::vector<Op> div_ops;
  for (uint32_t i = 0; i < (1u << T::kWidth); ++i) div_ops.push_back({T::one().bits(), i});
  h.run(div_ops, every_value<T>(), Spacing::kTight);
  finish(h,
         "rtl iterative fp24, 2 lanes, tightest spacing: every x through 1 / x and sqrt(x) "
         "(operations)");
}

template <class V>
void fp24_random(const Config& cfg, Spacing spacing, uint64_t randoms, uint64_t seed) {
  using T = fp24;
  IterHarness<V, T> h(cfg, seed);
  const std::vector<Op> ops = specials_and_random<T>(randoms, seed ^ 0x9e3779b97f4a7c15ull);
  h.run(ops, ops, spacing);
  finish(h, "rtl iterative fp24, " + std::to_string(cfg.lanes) + " lane(s), stages " +
                std::to_string(cfg.div_stages) + "/" + std::to_string(cfg.sqrt_stages) + ", " +
                (spacing == Spacing::kTight ? "tightest" : "random") +
                " spacing: special x special and " + std::to_string(randoms) +
                " random pairs through a / b and sqrt(a) (operations)");
}

TEST(FpIterRtl, Fp24RandomOneLane) {
  fp24_random<Vfp_iter_e7f16_l1>(kFp24L1, Spacing::kRandom, 500'000, 5);
}
TEST(FpIterRtl, Fp24RandomTwoLanesTight) {
  fp24_random<Vfp_iter_e7f16_l2>(kFp24L2, Spacing::kTight, 500'000, 6);
}
TEST(FpIterRtl, Fp24RandomTwoLanesLongerLatency) {
  fp24_random<Vfp_iter_e7f16_l2_s>(kFp24L2Long, Spacing::kRandom, 500'000, 7);
}

// Operation i + Lanes one cycle too soon: each unit's lane assertion stops the simulation.
template <class V>
void spacing_violation(bool div) {
  using T = fp24;
  IterHarness<V, T> h(kFp24L2, 8, false);
  const std::vector<Op> ops(8, Op{T::one().bits(), T::one().bits()});
  const std::vector<Op> none;
  EXPECT_THROW(h.run(div ? ops : none, div ? none : ops, Spacing::kTight, 1), TbError);
}
TEST(FpIterRtl, DivSpacingViolationAsserts) { spacing_violation<Vfp_iter_e7f16_l2>(true); }
TEST(FpIterRtl, SqrtSpacingViolationAsserts) { spacing_violation<Vfp_iter_e7f16_l2>(false); }

}  // namespace
}  // namespace rc::test
