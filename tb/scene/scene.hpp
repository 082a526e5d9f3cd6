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

struct Light {
  enum class Type { kPoint, kDirectional };
  Type type = Type::kPoint;
  glm::dvec3 position{0.0, 0.0, 0.0};  // the direction the light travels, for directional lights
  glm::dvec3 color{1.0, 1.0, 1.0};
  double intensity = 1.0;
};

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
