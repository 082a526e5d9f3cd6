// Comparing two frames: hit agreement (same closest triangle, or both miss) and PSNR; and the
// bit-exact comparison of the RTL against the golden model (rgb, hit records, counters).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render.hpp"

namespace rc {

struct Agreement {
  uint64_t pixels = 0;
  uint64_t agree = 0;  // both miss, or both hit the same triangle
  uint64_t both_miss = 0;
  uint64_t only_a_hits = 0;    // a hits, b misses
  uint64_t only_b_hits = 0;    // b hits, a misses
  uint64_t different_tri = 0;  // both hit, different triangles
  uint64_t same_depth = 0;     // of those, hits within 0.1% of each other in t (shared edges,
                               // corners, coplanar overlapping triangles)
  double psnr_db = 0.0;        // of a's image against b's (inf when identical)
  double share() const {
    return pixels ? static_cast<double>(agree) / static_cast<double>(pixels) : 1.0;
  }
};

Agreement compare_frames(const Frame& a, const Frame& b);

// The shadow test's agreement (scene lighting): over the pixels where both frames hit the same
// triangle, each of the first `lights` lights (at most 32) counts once: agree when both say it
// reaches the hit or both say it does not (behind the surface or occluded).
struct LightAgreement {
  uint64_t tests = 0, agree = 0;
  uint64_t only_a_lit = 0, only_b_lit = 0;
  double share() const {
    return tests ? static_cast<double>(agree) / static_cast<double>(tests) : 1.0;
  }
};
LightAgreement compare_lights(const Frame& a, const Frame& b, size_t lights);

// The mirror rays' agreement (scene lighting): over the pixels where both frames hit the same
// triangle and at least one traces a mirror ray, agree when both trace one and its first hit is
// the same triangle (or both miss); only_one counts the pixels where one frame traces a mirror
// ray and the other does not (a weight that underflowed).
struct BounceAgreement {
  uint64_t rays = 0, agree = 0, only_one = 0;
  double share() const {
    return rays ? static_cast<double>(agree) / static_cast<double>(rays) : 1.0;
  }
};
BounceAgreement compare_bounces(const Frame& a, const Frame& b);
// The same for the refraction rays (Frame::refract_tri).
BounceAgreement compare_refractions(const Frame& a, const Frame& b);

// A difference image: pixels where the hits agree are the darkened image a; disagreeing pixels
// are red (different triangle), green (only a hits) or blue (only b hits).
std::vector<uint8_t> hit_difference_image(const Frame& a, const Frame& b);

// Bit-exact comparison: every pixel's rgb and exact hit record (Frame::hits, both frames must
// have them).
struct ExactComparison {
  uint64_t pixels = 0;
  uint64_t differing = 0;    // pixels whose rgb or hit record differ
  uint64_t rgb_differ = 0;   // of those, pixels whose rgb differs
  uint64_t hits_differ = 0;  // of those, pixels whose hit record differs
  int64_t first = -1;        // the first differing pixel (y * width + x), -1: none
  bool equal() const { return differing == 0; }
};
ExactComparison compare_exact(const Frame& expected, const Frame& actual);

// A difference image of the exact comparison: equal pixels are the darkened expected image;
// differing pixels are red (hit record differs), yellow (only rgb differs).
std::vector<uint8_t> exact_difference_image(const Frame& expected, const Frame& actual);

// A counter that differs between the golden model (expected) and the RTL (actual).
struct CounterDifference {
  std::string name;
  uint64_t expected = 0, actual = 0;
  // Must match: every counter for a frame without errors; after an error (expected.errors > 0)
  // only packets, rays, failed_packets and error_bits, since the failing packets' operations
  // already in flight still finish and count (docs/architecture.md, the core's counters).
  bool required = true;
  std::string text() const;  // "name: expected X, got Y"
};

// The counters the RTL reproduces: packets, rays, node fetches, inner visits, traversal steps,
// leaf visits, empty leaves, list entries, triangle tests, pushes, pops, culled pops, max stack,
// failed packets and the error bits. Empty: all equal.
std::vector<CounterDifference> counter_differences(const Counters& expected,
                                                   const Counters& actual);

}  // namespace rc
