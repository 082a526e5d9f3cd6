// fuzz_scene_json: libFuzzer target for the scene JSON reader, rc::scene::load_scene_json_text
// (tb/scene/scene.cpp, with nlohmann-json and the built-in procedural meshes of procedural.cpp).
//
// Input: the text of a scene .json (format in docs/memory-format.md; examples in scenes/ and
// corpus/fuzz_scene_json/). Meshes are meant to be built-in ("builtin": "cornell" ...): the base
// directory is this process's empty temporary directory, the build defines RC_SOURCE_DIR as a
// directory that does not exist, RAYCORE_MODELS_PATH is unset and the current directory is the
// temporary directory during each call, so a "path" mesh is normally not found and fails with an
// Error (an absolute path or one climbing out with ../ can still name a real file; that is read
// like any OBJ).
//
// Correct outcomes: a Scene, or rc::scene::Error (but not "internal error: ..."). Findings:
// sanitizer reports, other exceptions (e.g. nlohmann::json errors escaping the reader), hangs,
// huge allocations, and a returned Scene that breaks its invariants (no meshes, a mesh with bad
// indices, a resolution outside 1..16384, non-finite values). A scene of at most kCompileMax
// triangles is also compiled (fp24); its image must load and validate, and its view record's
// camera (the scene's, in float32) must pass the camera rule (scene::camera_problem).
//
// Build and run: `make fuzz` (tests/fuzz/fuzz.mk). By hand: build/fuzz/fuzz_scene_json CORPUS_DIR,
// or build/fuzz/fuzz_scene_json FILE to replay one input.
#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "compiler.hpp"
#include "error.hpp"
#include "fuzz_common.hpp"
#include "image.hpp"
#include "scene.hpp"

namespace {

constexpr size_t kCompileMax = 512;

using rc::fuzz::fuzz_fail;

// Runs in the temporary directory, back to the previous working directory afterwards (also when
// an exception leaves), so that the loader's "../shared/models" fallback finds nothing.
class InTempDir {
 public:
  explicit InTempDir(const std::string& dir) : fd_(open(".", O_RDONLY | O_DIRECTORY)) {
    if (fd_ < 0 || chdir(dir.c_str()) != 0) fuzz_fail("cannot change into " + dir);
  }
  ~InTempDir() {
    if (fchdir(fd_) != 0) fuzz_fail("cannot change back to the working directory");
    close(fd_);
  }
  InTempDir(const InTempDir&) = delete;
  InTempDir& operator=(const InTempDir&) = delete;

 private:
  int fd_;
};

bool finite3(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check_scene(const rc::scene::Scene& s) {
  if (s.meshes.empty()) fuzz_fail("load_scene_json_text returned a scene without meshes");
  for (size_t i = 0; i < s.meshes.size(); ++i) {
    const auto& m = s.meshes[i];
    const std::string at = "mesh " + std::to_string(i) + " (" + m.source + "): ";
    if (m.triangles.empty()) fuzz_fail(at + "no triangles");
    if (m.material.size() != m.triangles.size() || m.line.size() != m.triangles.size())
      fuzz_fail(at + "per-triangle arrays differ in length");
    for (size_t t = 0; t < m.triangles.size(); ++t) {
      for (uint32_t v : m.triangles[t])
        if (v >= m.vertices.size()) fuzz_fail(at + "vertex index out of range");
      if (m.material[t] >= m.materials.size()) fuzz_fail(at + "material index out of range");
    }
  }
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
    fuzz_fail("resolution " + std::to_string(s.width) + "x" + std::to_string(s.height) +
              " outside 1..16384");
  if (!finite3(s.background)) fuzz_fail("non-finite background");
  for (const auto& l : s.lights)
    if (!finite3(l.position) || !finite3(l.color) || !std::isfinite(l.intensity))
      fuzz_fail("non-finite light");
}

void compile_and_validate(const rc::scene::Scene& scene) {
  const rc::scene::Compiled c = rc::scene::compile_scene(scene, rc::scene::CompileOptions{});
  try {
    const auto img = rc::scene::SceneImage::from_bytes(c.image, "compiled");
    const auto problems = img.validate();
    if (!problems.empty()) fuzz_fail("the compiled image does not validate: " + problems.front());
    // The scene's camera passed the one camera rule (also for its float32 rounding), so the view
    // record's camera must pass it too: `raycore render` of the image takes that camera.
    const rc::scene::ViewRecord v = img.view();
    if (!(v.flags & rc::spec::kImageViewFlagAutoCamera)) {
      rc::scene::Camera cam;
      cam.eye = {v.eye[0], v.eye[1], v.eye[2]};
      cam.look = {v.look[0], v.look[1], v.look[2]};
      cam.up = {v.up[0], v.up[1], v.up[2]};
      cam.fov_deg = v.fov_deg;
      if (const auto problem = rc::scene::camera_problem(cam))
        fuzz_fail("the compiled image's view camera breaks the camera rule: " + problem->field +
                  ": " + problem->what);
    }
  } catch (const rc::scene::Error& e) {
    fuzz_fail(std::string("the compiled image does not load: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  unsetenv("RAYCORE_MODELS_PATH");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string& dir = rc::fuzz::temp_dir("json");
  try {
    rc::scene::Scene scene;
    {
      InTempDir in_dir(dir);
      scene = rc::scene::load_scene_json_text(text, "fuzz.json", dir, rc::scene::LoadOptions{});
    }
    check_scene(scene);
    size_t triangles = 0;
    for (const auto& m : scene.meshes) triangles += m.triangles.size();
    if (triangles <= kCompileMax) compile_and_validate(scene);
  } catch (const rc::scene::Error& e) {
    // Rejected input: a correct outcome (unless the message admits an internal error).
    rc::fuzz::check_error_message(e.what());
  } catch (...) {
    fuzz_fail(rc::fuzz::describe_current_exception());
  }
  return 0;
}
