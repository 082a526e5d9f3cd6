// Scene descriptions: what the compiler turns into a memory image.
//
// A scene is one or more meshes (OBJ files or built-in procedural meshes, each optionally
// transformed), a camera, the frame size, a background colour and lights. It comes from a JSON file
// (scenes/*.json, format in docs/memory-format.md), a bare OBJ file, or builtin:NAME.
#pragma once

#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "mesh.hpp"

namespace rc::scene {

struct Camera {
  glm::dvec3 eye{0.0, 0.0, 1.0};
  glm::dvec3 look{0.0, 0.0, 0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_deg = 45.0;  // vertical field of view
};

// The one camera rule of the project, used by `scene build` for scene files and by `render`
// (tb/golden's validate_camera(): the --camera option, a scene's camera, an image's view record):
//  - eye, look and up are finite and inside the float32 range (the image's view record stores
//    float32);
//  - the vertical fov is in [kMinFovDeg, kMaxFovDeg] degrees: below kMinFovDeg tan(fov/2) is so
//    small that the ray generator's pixel steps vanish in the core's format, above kMaxFovDeg the
//    directions through the image's corners grow without bound;
//  - look differs from eye, up is not zero, and up is not (nearly) parallel to the view direction:
//    |normalize(look - eye) x normalize(up)| >= kMinUpSine, so only the directions count, not the
//    lengths (an up of (0, 1e-12, 0) is as good as (0, 1, 0));
//  - and the last point holds again for the camera rounded to float32, as an image stores it.
// kMinUpSine (an angle of 0.0057 degrees) keeps the image's rotation caused by that rounding (at
// most 2^-24 / kMinUpSine radians) below 0.001 degrees.
inline constexpr double kMinFovDeg = 1e-3;
inline constexpr double kMaxFovDeg = 180.0 - 1e-3;
inline constexpr double kMinUpSine = 1e-4;

struct CameraProblem {
  std::string field;  // "eye", "look", "up" or "fov"
  std::string what;   // e.g. "must differ from eye"
};
// The first problem of the camera under the rule above, if any.
std::optional<CameraProblem> camera_problem(const Camera& cam);
// Throws Error("WHERE.FIELD: WHAT") for the first problem (WHERE is e.g. "camera" or
// "FILE: camera").
void check_camera(const Camera& cam, const std::string& where = "camera");

struct Light {
  enum class Type { kPoint, kDirectional };
  Type type = Type::kPoint;
  glm::dvec3 position{0.0, 0.0, 0.0};  // the direction the light travels, for directional lights
  glm::dvec3 color{1.0, 1.0, 1.0};
  double intensity = 1.0;
};

// The ranges a scene file's colours and light intensities must lie in (docs/memory-format.md,
// "Scene files"): the background and light colours are fractions per channel (the core shows the
// background as 8-bit RGB, 1 = 255), the intensity scales a light's colour.
inline constexpr double kMaxColour = 1.0;
inline constexpr double kMaxIntensity = 1e6;

struct Scene {
  std::string name;
  std::string source;            // the file or builtin:NAME it came from
  std::vector<Mesh> meshes;      // triangles are numbered over the meshes in this order
  std::optional<Camera> camera;  // none: placed automatically from the bounds
  uint32_t width = 256;
  uint32_t height = 192;
  glm::dvec3 background{0.0, 0.0, 0.0};
  std::vector<Light> lights;
};

struct LoadOptions {
  // Directories searched for mesh files (--models-path; ':' separates several).
  std::vector<std::string> models_path;
};

// The directories searched for a mesh path that is not found as given, in order: the scene file's
// directory (for meshes named in a JSON scene), each --models-path entry, each entry of the
// environment variable RAYCORE_MODELS_PATH, ../shared/models relative to the current directory,
// and ../shared/models relative to the repository root (baked in at build time).
std::vector<std::string> model_search_path(const LoadOptions& options);

// Resolves a mesh path: as given (absolute, or relative to the current directory), then relative
// to `base_dir` (if not empty), then through model_search_path(). Throws Error listing the places
// searched.
std::string find_model(const std::string& path, const std::string& base_dir,
                       const LoadOptions& options);

// Loads `input`: builtin:NAME, a .json scene file, or anything else as an OBJ file.
Scene load_scene(const std::string& input, const LoadOptions& options);
Scene load_scene_json_text(const std::string& text, const std::string& name,
                           const std::string& base_dir, const LoadOptions& options);

// The built-in procedural scenes (tb/scene/procedural.cpp).
std::vector<std::string> builtin_names();
Scene builtin_scene(const std::string& name);

// The automatic camera (docs/architecture.md, "Rays"), used when a scene has none and for
// --auto-camera: look = centre of the bounds, eye = look + normalize(0.3, 0.25, 1.0) * 1.6 *
// |diagonal|, up = +y, vertical fov 45 degrees. The bounds are the image's (rounded outwards).
Camera auto_camera(const glm::dvec3& lo, const glm::dvec3& hi);

// The repository root baked in at build time.
std::string source_root();

}  // namespace rc::scene
