// Surface-area-heuristic kd-tree build in O(N log N) (Wald and Havran 2006, "On building fast
// kd-trees for ray tracing, and on doing that in O(N log N)"), with split clipping ("perfect
// splits") and an empty-space bonus, for a traverser that computes in the image's number format.
//
// Split planes are values of the number format: a candidate plane is the format value just below a
// triangle's (clipped) minimum or just above its maximum, it must lie strictly inside the node, and
// triangles are classified against that exact value with closed boxes: a triangle goes left when
// its clipped box reaches down to the plane or below (lo <= s), right when it reaches up to it or
// above (hi >= s), to both when both hold. Node boxes are doubles whose faces are exactly the root
// bounds (format values) and the split values, so a traverser that reconstructs them from the image
// sees the same boxes. Clipped triangle boxes are computed conservatively (slightly enlarged, then
// intersected with the node), so every triangle reaches every leaf whose closed box it touches.
#pragma once

#include <array>
#include <cstdint>
#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "image.hpp"
#include "number_format.hpp"

namespace rc::scene {

struct Box {
  glm::dvec3 lo{0.0}, hi{0.0};
};

double surface_area(const Box& b);

static_assert(spec::kKdtreeMaxDepth <= spec::kKdtreeStackDepth,
              "a tree deeper than the traversal stack could overflow it");

struct KdParams {
  int max_depth = static_cast<int>(spec::kKdtreeMaxDepth);
  double traversal_cost = static_cast<double>(spec::kKdtreeTraversalCost);
  double intersection_cost = static_cast<double>(spec::kKdtreeIntersectionCost);
  double empty_bonus = static_cast<double>(spec::kKdtreeEmptyBonusPercent) / 100.0;
  double empty_min_fraction = static_cast<double>(spec::kKdtreeEmptyMinPercent) / 100.0;
  // A split must lower the tree's SAH cost by at least min_gain / N (N = triangles in the tree).
  double min_gain = static_cast<double>(spec::kKdtreeMinGain);
  // Both children of a split must be at least this many units in the last place (of the format,
  // at the largest coordinate of the root box) thick along the split axis.
  double min_extent_ulps = static_cast<double>(spec::kKdtreeMinExtentUlps);
};

struct KdTree {
  std::vector<KdNode> nodes;    // root at 0; children of an inner node are adjacent
  std::vector<uint32_t> lists;  // leaf triangle lists (triangle ids), ascending within a leaf
  Box bounds;                   // the root box
  // Statistics.
  uint32_t depth = 0;  // deepest leaf (root = 0)
  size_t inner = 0, leaves = 0, empty_leaves = 0;
  size_t max_leaf = 0;    // most triangles in one leaf
  double sah_cost = 0.0;  // expected cost per ray through the root box (see the docs)
};

// Builds the tree over the triangles tris[i] (vertex positions), whose ids in the image are ids[i].
// `root` must contain every triangle and have faces that are values of `format`.
KdTree build_kdtree(const std::vector<std::array<glm::dvec3, 3>>& tris,
                    const std::vector<uint32_t>& ids, const Box& root, const NumberFormat& format,
                    const KdParams& params = KdParams());

}  // namespace rc::scene
