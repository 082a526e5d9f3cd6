// Comparing two frames: hit agreement (same closest triangle, or both miss) and PSNR.
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

// A difference image: pixels where the hits agree are the darkened image a; disagreeing pixels
// are red (different triangle), green (only a hits) or blue (only b hits).
std::vector<uint8_t> hit_difference_image(const Frame& a, const Frame& b);

}  // namespace rc
