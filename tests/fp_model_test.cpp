// The C++ number-format model (tb/fp/fp.hpp) against an independent exact reference: MPFR
// computes each operation correctly rounded to p = F + 1 bits with an unbounded exponent; the
// format's flush/overflow rule and the encoding are then applied here without using the model.
#include <gtest/gtest.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "fp.hpp"
#include "fp_cases.hpp"

namespace rc::test {
namespace {

enum class Op { kAdd, kSub, kMul, kDiv, kMin, kMax };

const char* op_name(Op op) {
  switch (op) {
    case Op::kAdd: return "add";
    case Op::kSub: return "sub";
    case Op::kMul: return "mul";
    case Op::kDiv: return "div";
    case Op::kMin: return "min";
    case Op::kMax: return "max";
  }
  return "?";
}

// An MPFR workspace: operands at 53 bits (exact for every value of the format), result at p bits.
template <class T>
class Mpfr {
 public:
  Mpfr() {
    mpfr_init2(x_, 53);
    mpfr_init2(y_, 53);
    mpfr_init2(r_, T::kFracW + 1);
  }
  ~Mpfr() {
    mpfr_clear(x_);
    mpfr_clear(y_);
    mpfr_clear(r_);
  }
  Mpfr(const Mpfr&) = delete;
  Mpfr& operator=(const Mpfr&) = delete;

  // Encodes MPFR's rounded result in the format, applying flush-to-zero and overflow.
  uint32_t encode_result() const {
    if (mpfr_nan_p(r_)) return T::kQNaNBits;
    const uint32_t s = mpfr_signbit(r_) ? T::kSignBit : 0;
    if (mpfr_inf_p(r_)) return s | T::kInfBits;
    if (mpfr_zero_p(r_)) return s;
    const long e = static_cast<long>(mpfr_get_exp(r_)) - 1;  // |r| in [2^e, 2^(e+1))
    const long be = e + T::kBias;
    if (be <= 0) return s;
    if (be >= static_cast<long>(T::kExpMax)) return s | T::kInfBits;
    const double m = std::ldexp(std::fabs(mpfr_get_d(r_, MPFR_RNDN)), static_cast<int>(-e));
    const auto frac = static_cast<uint32_t>(std::ldexp(m - 1.0, T::kFracW));
    return s | (static_cast<uint32_t>(be) << T::kFracW) | frac;
  }

  // Rounds a double once (the format's from_double rule).
  uint32_t round(double v) {
    mpfr_set_d(r_, v, MPFR_RNDN);
    return encode_result();
  }

  uint32_t binary(Op op, T a, T b) {
    mpfr_set_d(x_, a.to_double(), MPFR_RNDN);
    mpfr_set_d(y_, b.to_double(), MPFR_RNDN);
    if ((op == Op::kMin || op == Op::kMax) && (mpfr_nan_p(x_) || mpfr_nan_p(y_)))
      return T::kQNaNBits;  // the format's rule; MPFR's min/max would return the number
    switch (op) {
      case Op::kAdd: mpfr_add(r_, x_, y_, MPFR_RNDN); break;
      case Op::kSub: mpfr_sub(r_, x_, y_, MPFR_RNDN); break;
      case Op::kMul: mpfr_mul(r_, x_, y_, MPFR_RNDN); break;
      case Op::kDiv: mpfr_div(r_, x_, y_, MPFR_RNDN); break;
      case Op::kMin: mpfr_min(r_, x_, y_, MPFR_RNDN); break;  // -0 below +0, as ours
      case Op::kMax: mpfr_max(r_, x_, y_, MPFR_RNDN); break;
    }
    return encode_result();
  }

  uint32_t sqrt(T a) {
    mpfr_set_d(x_, a.to_double(), MPFR_RNDN);
    mpfr_sqrt(r_, x_, MPFR_RNDN);  // sqrt(-0) = -0, NaN for a NaN and below zero, as ours
    return encode_result();
  }

  // Comparison results as bits: lt, le, eq.
  unsigned compare(T a, T b) {
    mpfr_set_d(x_, a.to_double(), MPFR_RNDN);
    mpfr_set_d(y_, b.to_double(), MPFR_RNDN);
    return (mpfr_less_p(x_, y_) ? 1u : 0u) | (mpfr_lessequal_p(x_, y_) ? 2u : 0u) |
           (mpfr_equal_p(x_, y_) ? 4u : 0u);
  }

 private:
  mpfr_t x_, y_, r_;
};

template <class T>
uint32_t model(Op op, T a, T b) {
  switch (op) {
    case Op::kAdd: return (a + b).bits();
    case Op::kSub: return (a - b).bits();
    case Op::kMul: return (a * b).bits();
    case Op::kDiv: return (a / b).bits();
    case Op::kMin: return min(a, b).bits();
    case Op::kMax: return max(a, b).bits();
  }
  return 0;
}

template <class T>
unsigned model_compare(T a, T b) {
  return (lt(a, b) ? 1u : 0u) | (le(a, b) ? 2u : 0u) | (eq(a, b) ? 4u : 0u);
}

// Checks one pair for every operation; returns the number of operations that mismatched.
template <class T>
uint64_t check_pair(Mpfr<T>& ref, T a, T b, uint64_t& reported) {
  uint64_t bad = 0;
  for (Op op : {Op::kAdd, Op::kSub, Op::kMul, Op::kDiv, Op::kMin, Op::kMax}) {
    const uint32_t want = ref.binary(op, a, b), got = model(op, a, b);
    if (want != got) {
      ++bad;
      if (reported++ < 10)
        ADD_FAILURE() << op_name(op) << "(" << a.hex() << ", " << b.hex() << "): model "
                      << T::from_bits(got).hex() << ", MPFR " << T::from_bits(want).hex();
    }
  }
  const unsigned want_c = ref.compare(a, b), got_c = model_compare(a, b);
  if (want_c != got_c) {
    ++bad;
    if (reported++ < 10)
      ADD_FAILURE() << "compare(" << a.hex() << ", " << b.hex() << "): model lt/le/eq bits "
                    << got_c << ", MPFR " << want_c;
  }
  return bad;
}

constexpr uint64_t kOpsPerPair = 7;  // add, sub, mul, div, min, max, compare(lt, le, eq)

template <class T>
void random_pairs(const std::string& label, uint64_t pairs, uint64_t seed) {
  Mpfr<T> ref;
  PairGen<T> gen(seed);
  uint64_t bad = 0, reported = 0;
  T a, b;
  for (uint64_t i = 0; i < pairs; ++i) {
    gen.next(a, b);
    bad += check_pair(ref, a, b, reported);
  }
  report_cases((label + " model vs MPFR, random pairs x 7 ops").c_str(), pairs * kOpsPerPair, bad);
  EXPECT_EQ(bad, 0u);
}

template <class T>
void special_pairs(const std::string& label) {
  Mpfr<T> ref;
  const auto sv = special_values<T>();
  uint64_t bad = 0, reported = 0, pairs = 0;
  for (T a : sv)
    for (T b : sv) {
      bad += check_pair(ref, a, b, reported);
      ++pairs;
    }
  report_cases((label + " model vs MPFR, special x special x 7 ops").c_str(), pairs * kOpsPerPair,
               bad);
  EXPECT_EQ(bad, 0u);
}

TEST(FpModel, ReducedFormatExhaustiveVsMpfr) {
  using T = fp_reduced;
  Mpfr<T> ref;
  uint64_t bad = 0, reported = 0;
  const uint64_t n = 1ull << T::kWidth;
  for (uint64_t i = 0; i < n; ++i)
    for (uint64_t j = 0; j < n; ++j)
      bad += check_pair(ref, T::from_bits(static_cast<uint32_t>(i)),
                        T::from_bits(static_cast<uint32_t>(j)), reported);
  report_cases("fp_reduced(1/5/6) model vs MPFR, all pairs x 7 ops", n * n * kOpsPerPair, bad);
  EXPECT_EQ(bad, 0u);
}

TEST(FpModel, Fp24SpecialValuesVsMpfr) { special_pairs<fp24>("fp24"); }
TEST(FpModel, Fp24RandomVsMpfr) { random_pairs<fp24>("fp24", 10'000'000, 0x5eed0024); }
TEST(FpModel, Fp32SpecialValuesVsMpfr) { special_pairs<fp32ftz>("fp32ftz"); }
TEST(FpModel, Fp32RandomVsMpfr) { random_pairs<fp32ftz>("fp32ftz", 2'000'000, 0x5eed0032); }

// The square root of each given value, model against MPFR; returns the mismatches.
template <class T>
uint64_t check_sqrt(Mpfr<T>& ref, T a, uint64_t& reported) {
  const uint32_t want = ref.sqrt(a), got = sqrt(a).bits();
  if (want == got) return 0;
  if (reported++ < 10)
    ADD_FAILURE() << "sqrt(" << a.hex() << "): model " << T::from_bits(got).hex() << ", MPFR "
                  << T::from_bits(want).hex();
  return 1;
}

// The square root of every bit pattern of the format.
template <class T>
void sqrt_exhaustive(const std::string& label) {
  Mpfr<T> ref;
  uint64_t bad = 0, reported = 0;
  const uint64_t n = uint64_t{1} << T::kWidth;
  for (uint64_t i = 0; i < n; ++i)
    bad += check_sqrt(ref, T::from_bits(static_cast<uint32_t>(i)), reported);
  report_cases((label + " model sqrt vs MPFR, every value").c_str(), n, bad);
  EXPECT_EQ(bad, 0u);
}

TEST(FpModel, ReducedFormatSqrtExhaustiveVsMpfr) {
  sqrt_exhaustive<fp_reduced>("fp_reduced(1/5/6)");
}
TEST(FpModel, Fp24SqrtExhaustiveVsMpfr) { sqrt_exhaustive<fp24>("fp24"); }

// fp32ftz: the special values and random encodings (half of them positive).
TEST(FpModel, Fp32SqrtVsMpfr) {
  using T = fp32ftz;
  Mpfr<T> ref;
  uint64_t bad = 0, reported = 0, cases = 0;
  for (T a : special_values<T>()) {
    bad += check_sqrt(ref, a, reported);
    ++cases;
  }
  std::mt19937_64 rng(0x5eed5a27);
  for (int i = 0; i < 4'000'000; ++i) {
    bad += check_sqrt(ref, T::from_bits(static_cast<uint32_t>(rng())), reported);
    ++cases;
  }
  report_cases("fp32ftz model sqrt vs MPFR, specials and random encodings", cases, bad);
  EXPECT_EQ(bad, 0u);
}

// Every fp24 value: reciprocal against MPFR, negate and absolute value against their bit rules,
// the exact conversion to float32 against ldexp, and the round trip through float32.
TEST(FpModel, Fp24UnaryExhaustive) {
  using T = fp24;
  Mpfr<T> ref;
  const T one = T::from_double(1.0);
  EXPECT_EQ(T::one().bits(), one.bits());
  EXPECT_EQ(fp_reduced::one().bits(), fp_reduced::from_double(1.0).bits());
  EXPECT_EQ(fp32ftz::one().bits(), fp32ftz::from_double(1.0).bits());
  uint64_t bad = 0, reported = 0;
  const uint32_t n = 1u << T::kWidth;
  const auto fail = [&](const char* what, T x) {
    ++bad;
    if (reported++ < 10) ADD_FAILURE() << what << " wrong for " << x.hex();
  };
  for (uint32_t i = 0; i < n; ++i) {
    const T x = T::from_bits(i);
    if ((one / x).bits() != ref.binary(Op::kDiv, one, x)) fail("reciprocal", x);
    if ((-x).bits() != (i ^ T::kSignBit)) fail("negate", x);
    if (x.abs().bits() != (i & ~T::kSignBit)) fail("abs", x);
    // float32 of the value, built independently of the model
    const uint32_t e = (i >> T::kFracW) & T::kExpMax, f = i & T::kFracMask;
    const bool neg = (i & T::kSignBit) != 0;
    float want;
    if (e == 0) {
      want = neg ? -0.0f : 0.0f;
    } else if (e == T::kExpMax) {
      want = f ? std::nanf("") : HUGE_VALF;
      if (neg) want = -want;
    } else {
      want = std::ldexp(1.0f + std::ldexp(static_cast<float>(f), -T::kFracW),
                        static_cast<int>(e) - T::kBias);
      if (neg) want = -want;
    }
    const float got = x.to_float();
    if (std::isnan(want) ? !std::isnan(got)
                         : (got != want || std::signbit(got) != std::signbit(want)))
      fail("to_float", x);
    const T back = T::from_float(got);
    if (back.bits() != (x.is_nan() ? T::kQNaNBits : x.canonical().bits()))
      fail("float32 round trip", x);
  }
  report_cases("fp24 unary (reciprocal, neg, abs, to_float, round trip), every value",
               uint64_t{n} * 5, bad);
  EXPECT_EQ(bad, 0u);
}

// Conversion from double (and so from float32): random doubles across and beyond the range, and
// doubles exactly at and beside rounding ties, against MPFR's single rounding.
TEST(FpModel, Fp24FromDoubleVsMpfr) {
  using T = fp24;
  Mpfr<T> ref;
  std::mt19937_64 rng(0x5eedd0b1e);
  std::uniform_real_distribution<double> mant(1.0, 2.0);
  std::uniform_int_distribution<int> expo(-T::kBias - 20, T::kBias + 20);
  uint64_t bad = 0, reported = 0, cases = 0;
  const auto check = [&](double v) {
    ++cases;
    const uint32_t want = ref.round(v), got = T::from_double(v).bits();
    if (want != got) {
      ++bad;
      if (reported++ < 10)
        ADD_FAILURE() << "from_double(" << v << "): model " << T::from_bits(got).hex() << ", MPFR "
                      << T::from_bits(want).hex();
    }
  };
  for (int i = 0; i < 5'000'000; ++i) {
    const double v = std::ldexp(mant(rng), expo(rng)) * ((rng() & 1) ? -1.0 : 1.0);
    check(v);
    // a value of the format, then exactly half an ulp above it (a tie), and just beside the tie
    const T x = T::from_double(v);
    if (x.is_nan() || x.is_inf() || x.is_zero()) continue;
    const double xd = x.to_double();
    const double half_ulp =
        std::ldexp(1.0, static_cast<int>(x.exp_field()) - T::kBias - T::kFracW - 1);
    check(xd + half_ulp);
    check(std::nextafter(xd + half_ulp, 0.0));
    check(std::nextafter(xd + half_ulp, HUGE_VAL));
  }
  for (double v : {0.0, -0.0, HUGE_VAL, -HUGE_VAL, std::nan(""), 5e-324, -5e-324, 1e300, -1e-300,
                   static_cast<double>(std::numeric_limits<float>::max()),
                   static_cast<double>(std::numeric_limits<float>::denorm_min())})
    check(v);
  report_cases("fp24 from_double vs MPFR (random, ties, beside ties, specials)", cases, bad);
  EXPECT_EQ(bad, 0u);
}

// Worst-case error of each arithmetic operation in ulps of the result's binade, measured against
// a 256-bit MPFR evaluation, over results that are normal numbers (flushed and overflowed results
// are covered by the bit-exact tests above). A correctly rounded operation measures 0.5.
template <class T>
void measure_ulps(const std::string& label, uint64_t pairs, uint64_t seed) {
  mpfr_t x, y, exact, err;
  mpfr_inits2(256, x, y, exact, err, static_cast<mpfr_ptr>(nullptr));
  PairGen<T> gen(seed);
  for (Op op : {Op::kAdd, Op::kSub, Op::kMul, Op::kDiv}) {
    double worst = 0.0;
    uint64_t counted = 0;
    T a, b;
    for (uint64_t i = 0; i < pairs; ++i) {
      gen.next(a, b);
      const T r = T::from_bits(model(op, a, b));
      if (r.is_nan() || r.is_inf() || r.is_zero()) continue;
      mpfr_set_d(x, a.to_double(), MPFR_RNDN);
      mpfr_set_d(y, b.to_double(), MPFR_RNDN);
      switch (op) {
        case Op::kAdd: mpfr_add(exact, x, y, MPFR_RNDN); break;
        case Op::kSub: mpfr_sub(exact, x, y, MPFR_RNDN); break;
        case Op::kMul: mpfr_mul(exact, x, y, MPFR_RNDN); break;
        default: mpfr_div(exact, x, y, MPFR_RNDN); break;
      }
      // ulp of the exact result's binade: 2^(exp - 1 - F), exp as MPFR counts it
      const long ulp_exp = static_cast<long>(mpfr_get_exp(exact)) - 1 - T::kFracW;
      mpfr_set_d(err, r.to_double(), MPFR_RNDN);
      mpfr_sub(err, err, exact, MPFR_RNDN);
      mpfr_abs(err, err, MPFR_RNDN);
      mpfr_div_2si(err, err, ulp_exp, MPFR_RNDN);
      worst = std::max(worst, mpfr_get_d(err, MPFR_RNDU));
      ++counted;
    }
    std::printf("[ulps] %s %s: worst error %.6f ulp over %llu normal results\n", label.c_str(),
                op_name(op), worst, static_cast<unsigned long long>(counted));
    EXPECT_LE(worst, 0.5) << op_name(op) << " is not correctly rounded";
    EXPECT_GT(counted, pairs / 4) << "too few normal results measured";
  }
  mpfr_clears(x, y, exact, err, static_cast<mpfr_ptr>(nullptr));
}

TEST(FpModel, Fp24WorstCaseUlps) { measure_ulps<fp24>("fp24", 2'000'000, 0x0c1b); }
TEST(FpModel, Fp32WorstCaseUlps) { measure_ulps<fp32ftz>("fp32ftz", 1'000'000, 0x0c1c); }

}  // namespace
}  // namespace rc::test
