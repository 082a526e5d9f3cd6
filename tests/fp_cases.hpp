// Test inputs for the number format: special and boundary values, and seeded random operand pairs
// that reach the interesting parts of each operation (cancellation, ties, overflow, flush).
#pragma once

#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "fp.hpp"

namespace rc::test {

// Every special and boundary encoding of the format, both signs.
template <class T>
std::vector<T> special_values() {
  constexpr uint32_t kF = T::kFracW;
  const uint32_t frac_max = T::kFracMask;
  const auto enc = [](uint32_t e, uint32_t f) { return (e << kF) | f; };
  const uint32_t bias = T::kBias, emax = T::kExpMax - 1;
  std::vector<uint32_t> mags = {
      0,                              // zero
      1,                              // smallest subnormal encoding (reads as zero)
      frac_max,                       // largest subnormal encoding
      enc(1, 0),                      // smallest normal
      enc(1, 1),                      // smallest normal + 1 ulp
      enc(1, frac_max),               // just below 2 * smallest normal
      enc(2, 0),                      //
      enc(bias, 0),                   // 1.0
      enc(bias, 1),                   // 1 + ulp
      enc(bias - 1, frac_max),        // 1 - ulp/2
      enc(bias, 1u << (kF - 1)),      // 1.5
      enc(bias, frac_max),            // 2 - ulp
      enc(bias + 1, 0),               // 2.0
      enc(bias + 1, 1u << (kF - 1)),  // 3.0
      enc(bias - 1, 0),               // 0.5
      enc(emax, 0),                   // largest power of two
      enc(emax, frac_max),            // largest normal
      enc(emax, frac_max - 1),        //
      enc(emax - 1, frac_max),        //
      enc(bias / 2, 0x5),             // small values whose products flush
      enc(bias + bias / 2, 0x5),      // large values whose products overflow
      T::kInfBits,                    // infinity
      T::kQNaNBits,                   // canonical NaN
      T::kInfBits | 1,                // NaN with another payload
      T::kInfBits | frac_max,         // NaN with all payload bits
  };
  std::vector<T> out;
  for (uint32_t m : mags) {
    out.push_back(T::from_bits(m));
    out.push_back(T::from_bits(m | T::kSignBit));
  }
  return out;
}

// Seeded random operands: uniform encodings, close exponents (cancellation and rounding ties in
// add/sub), operands near the range limits, and special values mixed in.
template <class T>
class PairGen {
 public:
  explicit PairGen(uint64_t seed) : rng_(seed), specials_(special_values<T>()) {}

  T any() { return T::from_bits(static_cast<uint32_t>(rng_())); }

  void next(T& a, T& b) {
    const uint32_t kind = static_cast<uint32_t>(rng_() % 16);
    a = any();
    if (kind < 6) {
      b = any();
    } else if (kind < 11) {
      // b's exponent within F+3 of a's: alignment shifts that keep guard and sticky bits busy
      const int32_t ea = static_cast<int32_t>(a.exp_field());
      const int32_t d = static_cast<int32_t>(rng_() % (2 * (T::kFracW + 4))) - (T::kFracW + 4);
      int32_t eb = ea + d;
      eb = eb < 1 ? 1 : (eb > static_cast<int32_t>(T::kExpMax) - 1 ? T::kExpMax - 1 : eb);
      uint32_t fb = static_cast<uint32_t>(rng_()) & T::kFracMask;
      if (kind == 10) fb = a.frac_field() ^ (1u << (rng_() % T::kFracW));  // near-equal
      b = T::from_bits((static_cast<uint32_t>(rng_() & 1) ? T::kSignBit : 0) |
                       (static_cast<uint32_t>(eb) << T::kFracW) | fb);
    } else if (kind < 13) {
      // exponents near the ends of the range: products and quotients overflow or flush
      const uint32_t span = 6;
      const auto edge = [&](bool high) {
        const uint32_t e = high ? T::kExpMax - 1 - static_cast<uint32_t>(rng_() % span)
                                : 1 + static_cast<uint32_t>(rng_() % span);
        return T::from_bits((static_cast<uint32_t>(rng_() & 1) ? T::kSignBit : 0) |
                            (e << T::kFracW) | (static_cast<uint32_t>(rng_()) & T::kFracMask));
      };
      a = edge(rng_() & 1);
      b = edge(rng_() & 1);
    } else {
      b = specials_[rng_() % specials_.size()];
      if (kind == 15) a = specials_[rng_() % specials_.size()];
      if (rng_() & 1) std::swap(a, b);
    }
  }

 private:
  std::mt19937_64 rng_;
  std::vector<T> specials_;
};

inline void report_cases(const char* what, uint64_t cases, uint64_t mismatches) {
  std::printf("[cases] %s: %llu cases, %llu mismatches\n", what,
              static_cast<unsigned long long>(cases), static_cast<unsigned long long>(mismatches));
  std::fflush(stdout);
}

}  // namespace rc::test
