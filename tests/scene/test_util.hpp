// Helpers shared by the scene compiler tests: an independent soundness check of a kd-tree image
// (exact-enough triangle/box overlap against the leaf boxes rebuilt from the stored splits), image
// patching, temporary files, the shared model list and running the raycore executable.
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "image.hpp"
#include "scene.hpp"

namespace rc::test {

using Tri = std::array<glm::dvec3, 3>;

// Prints the "[cases] <what>: N cases, M mismatches" line that `make test` collects.
void report_cases(const std::string& what, size_t cases, size_t mismatches);

// The triangles of a scene in image order (over all meshes), vertex positions in double.
std::vector<Tri> scene_triangles(const rc::scene::Scene& scene);

// Separating axis test of a triangle against the closed box [lo, hi] (box = min xyz, max xyz), in
// long double: the 3 box axes exactly, the triangle normal and the 9 edge cross products with a
// 64-bit significand.
bool tri_box_overlap(const std::array<double, 6>& box, const Tri& tri);

struct TreeCheck {
  size_t pairs = 0;     // (triangle, leaf it overlaps) pairs checked
  size_t missing = 0;   // of those, pairs where the leaf does not list the triangle
  size_t spurious = 0;  // list entries whose triangle does not overlap the leaf (allowed)
  size_t unsorted = 0;  // leaves whose list is not ascending
  size_t nodes = 0, leaves = 0;
  uint32_t depth = 0;
  double sah = 0.0;                   // SAH cost recomputed from the image's boxes and counts
  std::vector<std::string> problems;  // the first few missing pairs, described
};

// Walks every live triangle down the tree through every child box it overlaps and checks that
// each leaf reached lists it; also recomputes depth and SAH cost from the image alone.
TreeCheck check_tree(const rc::scene::SceneImage& img, const std::vector<Tri>& tris);

// Image patching: write a little-endian value, then make the checksum right again.
void patch(std::vector<uint8_t>* img, size_t offset, uint64_t value, int bytes);
void fix_checksum(std::vector<uint8_t>* img);
const rc::scene::SectionInfo& section_of(const rc::scene::SceneImage& img, uint32_t id);

// A fresh temporary directory for this process, and files in it.
std::string temp_dir();
std::string write_temp(const std::string& name, const std::string& text);
// A whole file's bytes (empty when it cannot be read), and writing bytes to a file.
std::vector<uint8_t> read_file(const std::string& path);
void write_file(const std::string& path, const std::vector<uint8_t>& bytes);

// The shared models directory (tests/models_dir.hpp: RAYCORE_MODELS_PATH or ../shared/models);
// empty if absent.
std::string models_dir();
// The .obj files listed in models/README.md ("a/{b,c}.obj" expanded), relative to models_dir().
std::vector<std::string> readme_models();
// scenes/*.json of the repository, sorted.
std::vector<std::string> repo_scenes();

struct RunResult {
  int status = -1;     // exit status, or -1 if the process did not exit normally
  std::string output;  // stdout and stderr
};
// Runs the raycore executable with the arguments (shell-quoted here), with a time limit.
RunResult run_raycore(const std::vector<std::string>& args);

}  // namespace rc::test
