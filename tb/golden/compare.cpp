#include "compare.hpp"

#include <cmath>
#include <cstring>
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

ExactComparison compare_exact(const Frame& expected, const Frame& actual) {
  if (expected.width != actual.width || expected.height != actual.height)
    throw std::runtime_error("compare: frames differ in size");
  const size_t n = static_cast<size_t>(expected.width) * expected.height;
  if (expected.hits.size() != n || actual.hits.size() != n || expected.rgb.size() != 3 * n ||
      actual.rgb.size() != 3 * n)
    throw std::runtime_error("compare: a frame has no exact hit records");
  ExactComparison r;
  r.pixels = n;
  for (size_t i = 0; i < n; ++i) {
    const bool rgb = std::memcmp(&expected.rgb[3 * i], &actual.rgb[3 * i], 3) != 0;
    const bool hit = expected.hits[i] != actual.hits[i];
    if (!rgb && !hit) continue;
    ++r.differing;
    r.rgb_differ += rgb;
    r.hits_differ += hit;
    if (r.first < 0) r.first = static_cast<int64_t>(i);
  }
  return r;
}

std::vector<uint8_t> exact_difference_image(const Frame& expected, const Frame& actual) {
  const ExactComparison check = compare_exact(expected, actual);  // checks the sizes
  (void)check;
  std::vector<uint8_t> out(expected.rgb.size());
  for (size_t i = 0; i < expected.hits.size(); ++i) {
    uint8_t* p = &out[3 * i];
    const bool rgb = std::memcmp(&expected.rgb[3 * i], &actual.rgb[3 * i], 3) != 0;
    const bool hit = expected.hits[i] != actual.hits[i];
    if (hit) {
      p[0] = 255, p[1] = 0, p[2] = 0;
    } else if (rgb) {
      p[0] = 255, p[1] = 255, p[2] = 0;
    } else {
      for (int c = 0; c < 3; ++c) p[c] = static_cast<uint8_t>(expected.rgb[3 * i + c] / 3);
    }
  }
  return out;
}

std::string CounterDifference::text() const {
  return name + ": expected " + std::to_string(expected) + ", got " + std::to_string(actual);
}

std::vector<CounterDifference> counter_differences(const Counters& expected,
                                                   const Counters& actual) {
  std::vector<CounterDifference> out;
  const bool after_error = expected.errors > 0;
  const auto check = [&](const char* name, uint64_t e, uint64_t a, bool always) {
    if (e != a) out.push_back({name, e, a, always || !after_error});
  };
  check("packets", expected.packets, actual.packets, true);
  check("rays", expected.rays, actual.rays, true);
  check("nodes_fetched", expected.nodes_fetched, actual.nodes_fetched, false);
  check("inner_visits", expected.inner_visits, actual.inner_visits, false);
  check("traversal_steps", expected.traversal_steps, actual.traversal_steps, false);
  check("leaf_visits", expected.leaf_visits, actual.leaf_visits, false);
  check("empty_leaves", expected.empty_leaves, actual.empty_leaves, false);
  check("list_entries", expected.list_entries, actual.list_entries, false);
  check("triangle_tests", expected.triangle_tests, actual.triangle_tests, false);
  check("stack_pushes", expected.stack_pushes, actual.stack_pushes, false);
  check("stack_pops", expected.stack_pops, actual.stack_pops, false);
  check("culled_pops", expected.culled_pops, actual.culled_pops, false);
  check("max_stack", expected.max_stack, actual.max_stack, false);
  check("failed_packets", expected.errors, actual.errors, true);
  check("error_bits", expected.error_bits, actual.error_bits, true);
  return out;
}

LightAgreement compare_lights(const Frame& a, const Frame& b, size_t lights) {
  LightAgreement la;
  if (a.light_mask.size() != a.hit_tri.size() || b.light_mask.size() != b.hit_tri.size() ||
      a.hit_tri.size() != b.hit_tri.size())
    return la;
  const size_t n = lights < 32 ? lights : 32;
  for (size_t p = 0; p < a.hit_tri.size(); ++p) {
    if (a.hit_tri[p] < 0 || a.hit_tri[p] != b.hit_tri[p]) continue;
    for (size_t l = 0; l < n; ++l) {
      const bool la_lit = (a.light_mask[p] >> l & 1u) != 0,
                 lb_lit = (b.light_mask[p] >> l & 1u) != 0;
      ++la.tests;
      if (la_lit == lb_lit)
        ++la.agree;
      else if (la_lit)
        ++la.only_a_lit;
      else
        ++la.only_b_lit;
    }
  }
  return la;
}

namespace {

// The agreement of one child ray's first hit (Frame::bounce_tri or Frame::refract_tri).
BounceAgreement compare_first_hits(const Frame& a, const Frame& b,
                                   std::vector<int32_t> Frame::*first) {
  BounceAgreement ba;
  const std::vector<int32_t>&fa = a.*first, &fb = b.*first;
  if (fa.size() != a.hit_tri.size() || fb.size() != b.hit_tri.size() ||
      a.hit_tri.size() != b.hit_tri.size())
    return ba;
  for (size_t p = 0; p < a.hit_tri.size(); ++p) {
    if (a.hit_tri[p] < 0 || a.hit_tri[p] != b.hit_tri[p]) continue;
    const bool ra = fa[p] != -2, rb = fb[p] != -2;
    if (!ra && !rb) continue;
    ++ba.rays;
    if (ra && rb && fa[p] == fb[p])
      ++ba.agree;
    else if (ra != rb)
      ++ba.only_one;
  }
  return ba;
}

}  // namespace

BounceAgreement compare_bounces(const Frame& a, const Frame& b) {
  return compare_first_hits(a, b, &Frame::bounce_tri);
}

BounceAgreement compare_refractions(const Frame& a, const Frame& b) {
  return compare_first_hits(a, b, &Frame::refract_tri);
}

}  // namespace rc
