#include "number_format.hpp"

#include <cmath>

#include "error.hpp"
#include "fp.hpp"

namespace rc::scene {
namespace {

template <class T>
double round_to(double x) {
  return T::from_double(x).to_double();
}

template <class T>
uint32_t encode_as(double x) {
  const T t = T::from_double(x);
  return t.is_zero() ? 0u : t.bits();  // every zero is stored as +0
}

template <class T>
double decode_as(uint32_t bits) {
  return T::from_bits(bits).to_double();
}

template <class T>
double next_up_in(double v) {
  const T t = T::from_double(v);
  if (t.is_nan() || t.is_inf()) return t.to_double();
  if (t.is_zero()) return T::min_normal().to_double();
  if (!t.sign()) return T::from_bits(t.bits() + 1).to_double();  // max_normal + 1 is +inf
  if (t.bits() == T::min_normal(true).bits()) return 0.0;
  return T::from_bits(t.bits() - 1).to_double();
}

template <class T>
const NumberFormat::Ops* ops_for() {
  static const NumberFormat::Ops ops{&round_to<T>, &encode_as<T>, &decode_as<T>, &next_up_in<T>,
                                     T::max_normal().to_double()};
  return &ops;
}

}  // namespace

NumberFormat NumberFormat::fp24() { return {fp24::kExpW, fp24::kFracW, ops_for<rc::fp24>()}; }
NumberFormat NumberFormat::fp32() {
  return {fp32ftz::kExpW, fp32ftz::kFracW, ops_for<rc::fp32ftz>()};
}

NumberFormat NumberFormat::from_widths(int exp_w, int frac_w) {
  if (exp_w == rc::fp24::kExpW && frac_w == rc::fp24::kFracW) return fp24();
  if (exp_w == rc::fp32ftz::kExpW && frac_w == rc::fp32ftz::kFracW) return fp32();
  throw Error("unsupported number format " + std::to_string(exp_w) + "/" + std::to_string(frac_w) +
              " (exponent/fraction bits): supported are " + fp24().name() + " and " +
              fp32().name());
}

NumberFormat NumberFormat::parse(const std::string& text) {
  if (text == "fp24") return fp24();
  if (text == "fp32") return fp32();
  const auto slash = text.find('/');
  if (slash != std::string::npos && slash > 0 && slash + 1 < text.size() &&
      text.find_first_not_of("0123456789/") == std::string::npos &&
      text.find('/', slash + 1) == std::string::npos && slash < 4 && text.size() - slash < 5) {
    return from_widths(std::stoi(text.substr(0, slash)), std::stoi(text.substr(slash + 1)));
  }
  throw Error("bad number format '" + text +
              "': expected EXP/FRAC such as 7/16 (fp24) or 8/23 (fp32)");
}

std::string NumberFormat::name() const {
  std::string base = is<rc::fp24>() ? "fp24" : is<rc::fp32ftz>() ? "fp32" : "fp";
  return base + " (" + std::to_string(exp_w_) + "/" + std::to_string(frac_w_) + ")";
}

bool NumberFormat::finite_bits(uint32_t bits) const {
  const uint32_t exp_max = (1u << exp_w_) - 1;
  const uint64_t mask = (uint64_t{1} << width()) - 1;
  return bits <= mask && ((bits >> frac_w_) & exp_max) != exp_max;
}

}  // namespace rc::scene
