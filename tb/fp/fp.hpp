// raycore floating point: the C++ model of the core's number format (docs/fp24.md).
//
// Fp<E, F> is a value type holding one number of the format with 1 sign bit, E exponent bits and
// F fraction bits, flush-to-zero, round to nearest ties to even, with infinities and one canonical
// NaN. It is the single source of truth for the golden model: every operation here is what the RTL
// units compute, bit for bit.
//
// Implementation: each arithmetic operation is evaluated in double and rounded once to the target.
// Double has 53 significand bits; for a target of p = F + 1 <= 24 bits, 53 >= 2p + 2, so rounding
// the double result again to p bits gives the correctly rounded result of the exact operation
// (the double-rounding theorem for +, -, *, /; Figueroa 1995). The exponent range of double covers
// every intermediate of a format with E <= 9, so no double overflow or underflow can occur.
// tests/fp_model_test.cpp checks this against MPFR and exhaustively on a reduced format.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "rc_constants.hpp"

namespace rc {

template <int E, int F>
class Fp {
  static_assert(E >= 2 && E <= 9, "exponent width must be 2..9 (double must hold every result)");
  static_assert(F >= 1 && F <= 23, "fraction width must be 1..23 (double rounding must be exact)");

 public:
  static constexpr int kExpW = E;
  static constexpr int kFracW = F;
  static constexpr int kWidth = 1 + E + F;
  static constexpr int kBias = (1 << (E - 1)) - 1;
  static constexpr uint32_t kExpMax = (1u << E) - 1;  // exponent field of inf and NaN
  static constexpr uint32_t kFracMask = (1u << F) - 1;
  static constexpr uint32_t kSignBit = 1u << (E + F);
  static constexpr uint32_t kMask = (kSignBit << 1) - 1;
  static constexpr uint32_t kInfBits = kExpMax << F;
  static constexpr uint32_t kQNaNBits = kInfBits | (1u << (F - 1));  // the canonical NaN
  static constexpr uint32_t kMaxNormalBits = ((kExpMax - 1) << F) | kFracMask;
  static constexpr uint32_t kMinNormalBits = 1u << F;

  constexpr Fp() = default;
  static constexpr Fp from_bits(uint32_t b) { return Fp(b & kMask); }
  constexpr uint32_t bits() const { return bits_; }

  constexpr bool sign() const { return (bits_ & kSignBit) != 0; }
  constexpr uint32_t exp_field() const { return (bits_ >> F) & kExpMax; }
  constexpr uint32_t frac_field() const { return bits_ & kFracMask; }
  constexpr bool is_nan() const { return exp_field() == kExpMax && frac_field() != 0; }
  constexpr bool is_inf() const { return exp_field() == kExpMax && frac_field() == 0; }
  constexpr bool is_zero() const { return exp_field() == 0; }  // includes flushed encodings

  static constexpr Fp zero(bool neg = false) { return Fp(neg ? kSignBit : 0); }
  static constexpr Fp inf(bool neg = false) { return Fp(kInfBits | (neg ? kSignBit : 0)); }
  static constexpr Fp nan() { return Fp(kQNaNBits); }
  static constexpr Fp one() { return Fp(static_cast<uint32_t>(kBias) << F); }  // {0, bias, 0}
  static constexpr Fp max_normal(bool neg = false) {
    return Fp(kMaxNormalBits | (neg ? kSignBit : 0));
  }
  static constexpr Fp min_normal(bool neg = false) {
    return Fp(kMinNormalBits | (neg ? kSignBit : 0));
  }

  // The exact value as a double (every value of the format is a double). Encodings with a zero
  // exponent field read as signed zero.
  double to_double() const {
    const uint64_t s = static_cast<uint64_t>(sign()) << 63;
    const uint32_t e = exp_field();
    uint64_t d;
    if (e == 0) {
      d = s;
    } else if (e == kExpMax) {
      d = s | (0x7ffull << 52) | (static_cast<uint64_t>(frac_field()) << (52 - F));
    } else {
      d = s | (static_cast<uint64_t>(static_cast<int>(e) - kBias + 1023) << 52) |
          (static_cast<uint64_t>(frac_field()) << (52 - F));
    }
    double r;
    std::memcpy(&r, &d, sizeof r);
    return r;
  }

  // Exact conversion to float32 (needs E <= 8): sign, re-biased exponent, fraction shifted left.
  // Zero-exponent encodings give signed zero; a NaN stays a NaN.
  float to_float() const {
    static_assert(E <= 8, "to_float needs an exponent no wider than float32's");
    return static_cast<float>(to_double());
  }

  // Rounds a double once to the format: round to nearest, ties to even, with an unbounded exponent;
  // then a result whose exponent is below the smallest normal becomes signed zero and one above the
  // largest becomes signed infinity. Any NaN becomes the canonical NaN.
  static Fp from_double(double x) {
    uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    const uint32_t s = (u >> 63) ? kSignBit : 0;
    const uint64_t a = u & ~(1ull << 63);
    if (a >= (0x7ffull << 52)) return a == (0x7ffull << 52) ? Fp(s | kInfBits) : nan();
    constexpr int kSh = 52 - F;
    // Round the fraction to F bits; a carry out of the fraction increments the exponent.
    const uint64_t r = (a + ((1ull << (kSh - 1)) - 1) + ((a >> kSh) & 1)) >> kSh;
    const int64_t dexp = static_cast<int64_t>(r >> F);
    const int64_t e = dexp - 1023 + kBias;
    if (dexp == 0 || e <= 0) return Fp(s);
    if (e >= static_cast<int64_t>(kExpMax)) return Fp(s | kInfBits);
    return Fp(s | (static_cast<uint32_t>(e) << F) | static_cast<uint32_t>(r & kFracMask));
  }
  static Fp from_float(float x) { return from_double(static_cast<double>(x)); }

  // Zero-exponent encodings become signed zero with a zero fraction; everything else is kept.
  constexpr Fp canonical() const { return is_zero() ? Fp(bits_ & kSignBit) : *this; }

  friend Fp operator+(Fp a, Fp b) { return from_double(a.to_double() + b.to_double()); }
  friend Fp operator-(Fp a, Fp b) { return from_double(a.to_double() - b.to_double()); }
  friend Fp operator*(Fp a, Fp b) { return from_double(a.to_double() * b.to_double()); }
  friend Fp operator/(Fp a, Fp b) { return from_double(a.to_double() / b.to_double()); }
  // Square root, correctly rounded (double's sqrt is correctly rounded and 53 >= 2(F+1)+2 makes
  // rounding it again to F+1 bits innocuous): sqrt(+-0) = +-0, sqrt(+inf) = +inf, and any NaN
  // or negative nonzero input (a zero-exponent encoding reads as zero) gives the canonical NaN.
  friend Fp sqrt(Fp a) {
    if (a.is_zero()) return Fp(a.bits_ & kSignBit);
    return from_double(std::sqrt(a.to_double()));
  }
  Fp& operator+=(Fp b) { return *this = *this + b; }
  Fp& operator-=(Fp b) { return *this = *this - b; }
  Fp& operator*=(Fp b) { return *this = *this * b; }
  Fp& operator/=(Fp b) { return *this = *this / b; }

  // Bit operations on the sign, as IEEE 754 defines them: no canonicalisation, NaN keeps its
  // payload.
  constexpr Fp operator-() const { return Fp(bits_ ^ kSignBit); }
  constexpr Fp abs() const { return Fp(bits_ & ~kSignBit); }

  // IEEE comparisons: false when either side is NaN, -0 == +0.
  friend bool lt(Fp a, Fp b) { return a.to_double() < b.to_double(); }
  friend bool le(Fp a, Fp b) { return a.to_double() <= b.to_double(); }
  friend bool eq(Fp a, Fp b) { return a.to_double() == b.to_double(); }

  // NaN if either is NaN; otherwise the smaller (larger) value, with -0 below +0; canonical result.
  friend Fp min(Fp a, Fp b) {
    if (a.is_nan() || b.is_nan()) return nan();
    const Fp ca = a.canonical(), cb = b.canonical();
    const double da = ca.to_double(), db = cb.to_double();
    if (da != db) return da < db ? ca : cb;
    return Fp(ca.bits_ | cb.bits_);  // equal: identical bits, or two zeros where -0 wins
  }
  friend Fp max(Fp a, Fp b) {
    if (a.is_nan() || b.is_nan()) return nan();
    const Fp ca = a.canonical(), cb = b.canonical();
    const double da = ca.to_double(), db = cb.to_double();
    if (da != db) return da > db ? ca : cb;
    return Fp(ca.bits_ & cb.bits_);  // equal: identical bits, or two zeros where +0 wins
  }

  std::string hex() const {
    static const char* digits = "0123456789abcdef";
    std::string out = "0x";
    for (int shift = ((kWidth + 3) / 4 - 1) * 4; shift >= 0; shift -= 4)
      out += digits[(bits_ >> shift) & 0xf];
    return out;
  }

 private:
  constexpr explicit Fp(uint32_t b) : bits_(b) {}
  uint32_t bits_ = 0;
};

using fp24 = Fp<spec::kFp24ExpW, spec::kFp24FracW>;
using fp_reduced = Fp<spec::kFpReducedExpW, spec::kFpReducedFracW>;
using fp32ftz = Fp<spec::kFp32ExpW, spec::kFp32FracW>;

}  // namespace rc
