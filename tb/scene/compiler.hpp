// The scene compiler: scene -> unit-triangle transforms, SAH kd-tree -> one memory image, plus the
// build statistics.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "kdtree.hpp"
#include "number_format.hpp"
#include "scene.hpp"

namespace rc::scene {

struct CompileOptions {
  NumberFormat format = NumberFormat::fp24();
  KdParams kd;
};

struct SectionStat {
  std::string name;
  uint32_t id = 0;
  uint64_t offset = 0, bytes = 0, count = 0, stride = 0;
};

// What `raycore scene build` prints (docs/memory-format.md, "Build statistics").
struct BuildStats {
  std::string input, scene_name, format;
  size_t meshes = 0, vertices = 0, triangles = 0, dropped = 0, materials = 0, lights = 0;
  std::array<double, 6> bounds{};  // the root box (format values): min xyz, max xyz
  size_t nodes = 0, inner = 0, leaves = 0, empty_leaves = 0;
  size_t references = 0;   // leaf list entries
  double mean_leaf = 0.0;  // triangles per non-empty leaf (mean)
  size_t max_leaf = 0;
  uint32_t depth = 0;
  int depth_limit = 0;
  double sah_cost = 0.0;
  std::vector<SectionStat> sections;
  uint64_t image_bytes = 0;
  uint32_t checksum = 0;
  double load_ms = 0.0;       // reading and parsing the input (set by the caller)
  double transform_ms = 0.0;  // checks, unit-triangle transforms, shading records
  double build_ms = 0.0;      // the kd-tree build
  double write_ms = 0.0;      // assembling the image
  std::vector<std::string> warnings;
};

struct Compiled {
  std::vector<uint8_t> image;
  BuildStats stats;
};

// The unit-triangle transform of triangle (a, b, c), in double: rows m0, m1, m2 of the 3x4 matrix M
// with M(a,1) = 0, M(b,1) = (1,0,0), M(c,1) = (0,1,0), M(a + n, 1) = (0,0,1), n = (b-a) x (c-a).
// Returns false when n is zero (the triangle has no area).
bool unit_triangle_transform(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                             std::array<double, 12>* m);

// Throws Error for an empty scene, for vertex coordinates that are NaN, infinite or outside the
// format's range (naming the triangle and the file), and when nothing is left after dropping the
// degenerate triangles.
Compiled compile_scene(const Scene& scene, const CompileOptions& options);

void print_stats(std::ostream& out, const BuildStats& stats);
nlohmann::json stats_to_json(const BuildStats& stats);

}  // namespace rc::scene
