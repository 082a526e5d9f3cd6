// What a render needs, from any input the command line takes: a scene (JSON, OBJ, builtin:NAME),
// compiled to a memory image in memory, or a memory image file.
#pragma once

#include <optional>
#include <string>

#include "compiler.hpp"
#include "image.hpp"
#include "render.hpp"
#include "scene.hpp"

namespace rc {

struct RenderInput {
  std::string name;
  std::optional<scene::Scene> scene;  // absent for an .rcimg input
  scene::SceneImage image;
  std::optional<scene::BuildStats> build;  // when compiled here
  // The scene's camera in double, when the input is a scene that names one: input_options() takes
  // it before the image's view record, which holds it in float32.
  std::optional<scene::Camera> camera;
};

// Loads `input`; a path ending in .rcimg is read as an image, anything else is loaded as a scene
// and compiled with `format`. Throws rc::scene::Error naming the problem.
RenderInput load_render_input(const std::string& input, const scene::LoadOptions& load,
                              const scene::NumberFormat& format);

// Runs the image's validation (the checks of `raycore scene info`: tree, list ranges, records,
// bounds, materials, lights) and throws rc::scene::Error naming the problems when it finds any.
// Every engine's input passes through it before a render starts.
void require_valid(const scene::SceneImage& image);

// The render options the input itself asks for: its camera (or the automatic camera when it has
// none), its frame size and background colour.
RenderOptions input_options(const RenderInput& in);

// The automatic camera for the image's scene bounds.
Camera auto_camera_for(const scene::SceneImage& img);

}  // namespace rc
