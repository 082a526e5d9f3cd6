#include "compare.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rc {

Agreement compare_frames(const Frame& a, const Frame& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::runtime_error("compare: frames differ in size");
  Agreement r;
  r.pixels = a.hit_tri.size();
  for (size_t i = 0; i < a.hit_tri.size(); ++i) {
    const int32_t ta = a.hit_tri[i], tb = b.hit_tri[i];
    if (ta == tb) {
      ++r.agree;
      if (ta < 0) ++r.both_miss;
    } else if (tb < 0) {
      ++r.only_a_hits;
    } else if (ta < 0) {
      ++r.only_b_hits;
    } else {
      ++r.different_tri;
      const double da = a.hit_t[i], db = b.hit_t[i];
      if (std::fabs(da - db) <= 1e-3 * std::fabs(db)) ++r.same_depth;
    }
  }
  double se = 0.0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    const double d = static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i]);
    se += d * d;
  }
  const double mse = a.rgb.empty() ? 0.0 : se / static_cast<double>(a.rgb.size());
  r.psnr_db =
      mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
  return r;
}

std::vector<uint8_t> hit_difference_image(const Frame& a, const Frame& b) {
  std::vector<uint8_t> out(a.rgb.size());
  for (size_t i = 0; i < a.hit_tri.size(); ++i) {
    const int32_t ta = a.hit_tri[i], tb = b.hit_tri[i];
    uint8_t* p = &out[3 * i];
    if (ta == tb) {
      for (int c = 0; c < 3; ++c) p[c] = static_cast<uint8_t>(a.rgb[3 * i + c] / 3);
    } else {
      p[0] = (ta >= 0 && tb >= 0) ? 255 : 0;
      p[1] = (ta >= 0 && tb < 0) ? 255 : 0;
      p[2] = (ta < 0 && tb >= 0) ? 255 : 0;
    }
  }
  return out;
}

}  // namespace rc
