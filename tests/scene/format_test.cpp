// The run-time number format the image is written in: parsing, rounding helpers and neighbours,
// checked against rc::Fp directly and by brute force over the representable values near zero and
// the extremes.
#include <gtest/gtest.h>

#include <cmath>

#include "error.hpp"
#include "fp.hpp"
#include "number_format.hpp"
#include "test_util.hpp"

namespace rc::test {
namespace {

using rc::scene::NumberFormat;

TEST(NumberFormat, Parse) {
  EXPECT_TRUE(NumberFormat::parse("7/16") == NumberFormat::fp24());
  EXPECT_TRUE(NumberFormat::parse("fp24") == NumberFormat::fp24());
  EXPECT_TRUE(NumberFormat::parse("8/23") == NumberFormat::fp32());
  EXPECT_EQ(NumberFormat::fp24().value_bytes(), 3);
  EXPECT_EQ(NumberFormat::fp32().value_bytes(), 4);
  EXPECT_EQ(NumberFormat::fp24().name(), "fp24 (7/16)");
  for (const char* bad : {"", "7", "7/", "/16", "7/16/1", "a/b", "5/6", "8/16", "-7/16", "99999/1"})
    EXPECT_THROW(NumberFormat::parse(bad), rc::scene::Error) << bad;
}

template <class T>
void check_neighbours(const NumberFormat& f, const std::string& what) {
  size_t cases = 0, bad = 0;
  // Every finite positive and negative encoding with a small or large exponent, and some between.
  std::vector<uint32_t> bits;
  for (uint32_t e : {1u, 2u, 3u, T::kExpMax / 2, T::kExpMax - 2, T::kExpMax - 1})
    for (uint32_t frac : {0u, 1u, 2u, T::kFracMask / 2, T::kFracMask - 1, T::kFracMask})
      for (uint32_t s : {0u, T::kSignBit}) bits.push_back(s | (e << T::kFracW) | frac);
  bits.push_back(0);
  for (uint32_t b : bits) {
    const size_t bad_before = bad;
    const T v = T::from_bits(b);
    const double x = v.to_double();
    const double up = f.next_up(x), down = f.next_down(x);
    // next_up is the smallest value above x: nothing of the format lies strictly between.
    ++cases;
    bad += !(up > x) || !(down < x) || f.round(up) != up || f.round(down) != down;
    const double mid_up = x + (up - x) / 4, mid_down = x - (x - down) / 4;
    ++cases;
    if (std::isfinite(up))
      bad += f.above(x) != up || f.below(mid_up) != x || f.round_up(mid_up) != up;
    ++cases;
    if (std::isfinite(down))
      bad += f.below(x) != down || f.above(mid_down) != x || f.round_down(mid_down) != down;
    ++cases;
    bad += f.encode(x) != (v.is_zero() ? 0u : b) || f.decode(f.encode(x)) != x;
    if (bad != bad_before) ADD_FAILURE() << what << ": value " << v.hex() << " = " << x;
  }
  // Flush-to-zero: nothing between 0 and the smallest normal.
  const double tiny = T::min_normal().to_double();
  ++cases;
  bad += f.next_up(0.0) != tiny || f.next_down(0.0) != -tiny || f.above(tiny / 2) != tiny ||
         f.below(tiny / 2) != 0.0 || f.below(-tiny / 2) != -tiny || f.encode(-0.0) != 0u ||
         f.encode(-tiny / 4) != 0u;
  ++cases;
  bad += !std::isinf(f.next_up(f.max_value())) || f.round_up(f.max_value()) != f.max_value();
  report_cases(what + " neighbours and directed rounding", cases, bad);
  EXPECT_EQ(bad, 0u);
}

TEST(NumberFormat, NeighboursFp24) { check_neighbours<rc::fp24>(NumberFormat::fp24(), "fp24"); }
TEST(NumberFormat, NeighboursFp32) { check_neighbours<rc::fp32ftz>(NumberFormat::fp32(), "fp32"); }

}  // namespace
}  // namespace rc::test
