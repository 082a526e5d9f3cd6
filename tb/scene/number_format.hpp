// The number format of a memory image, chosen at run time.
//
// The image stores every geometric value in one format: fp24 (1 sign, 7 exponent, 16 fraction bits)
// by default, or float32 with our flush-to-zero rules (8/23) for the precision study. All rounding
// is done by rc::Fp<E, F> (tb/fp/fp.hpp): a value computed in double is rounded once with
// Fp::from_double. This class only dispatches to the right Fp instantiation.
#pragma once

#include <cstdint>
#include <string>

namespace rc::scene {

class NumberFormat {
 public:
  // fp24 (rc::fp24, the default) and fp32 (rc::fp32ftz).
  static NumberFormat fp24();
  static NumberFormat fp32();
  // Throws rc::scene::Error for a width pair that has no Fp instantiation here.
  static NumberFormat from_widths(int exp_w, int frac_w);
  // "7/16", "8/23", "fp24" or "fp32"; throws rc::scene::Error otherwise.
  static NumberFormat parse(const std::string& text);

  int exp_w() const { return exp_w_; }
  int frac_w() const { return frac_w_; }
  int width() const { return 1 + exp_w_ + frac_w_; }
  // Bytes per value where values are packed (triangle records, shading normals): ceil(width / 8).
  int value_bytes() const { return (width() + 7) / 8; }
  // "fp24 (7/16)".
  std::string name() const;

  // Round to nearest, ties to even, flush-to-zero, overflow to infinity (Fp::from_double).
  double round(double x) const { return ops_->round(x); }
  // The bit pattern of round(x); zero is always +0.
  uint32_t encode(double x) const { return ops_->encode(x); }
  // The exact value of a bit pattern (zero-exponent encodings read as zero).
  double decode(uint32_t bits) const { return ops_->decode(bits); }
  bool finite_bits(uint32_t bits) const;
  // The largest finite value.
  double max_value() const { return ops_->max_value; }

  // Neighbours of a finite value v of the format (next_up(max) is +inf; the neighbours of zero are
  // +-min_normal, flush-to-zero leaves nothing between).
  double next_up(double v) const { return ops_->next_up(v); }
  double next_down(double v) const { return -ops_->next_up(-v); }
  // The largest value of the format strictly below x, the smallest strictly above x.
  double below(double x) const {
    const double r = round(x);
    return r < x ? r : next_down(r);
  }
  double above(double x) const {
    const double r = round(x);
    return r > x ? r : next_up(r);
  }
  // Directed rounding: the largest value <= x, the smallest value >= x.
  double round_down(double x) const {
    const double r = round(x);
    return r <= x ? r : next_down(r);
  }
  double round_up(double x) const {
    const double r = round(x);
    return r >= x ? r : next_up(r);
  }

  template <class T>
  bool is() const {
    return T::kExpW == exp_w_ && T::kFracW == frac_w_;
  }
  friend bool operator==(const NumberFormat& a, const NumberFormat& b) {
    return a.exp_w_ == b.exp_w_ && a.frac_w_ == b.frac_w_;
  }
  friend bool operator!=(const NumberFormat& a, const NumberFormat& b) { return !(a == b); }

  struct Ops {
    double (*round)(double);
    uint32_t (*encode)(double);
    double (*decode)(uint32_t);
    double (*next_up)(double);
    double max_value;
  };

 private:
  NumberFormat(int e, int f, const Ops* ops) : exp_w_(e), frac_w_(f), ops_(ops) {}
  int exp_w_;
  int frac_w_;
  const Ops* ops_;
};

}  // namespace rc::scene
