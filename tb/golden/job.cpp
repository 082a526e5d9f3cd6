#include "job.hpp"

#include <cmath>

#include "error.hpp"

namespace rc {

namespace {
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
uint8_t to_byte(double v) {
  return static_cast<uint8_t>(std::nearbyint(std::min(std::max(v, 0.0), 1.0) * 255.0));
}
}  // namespace

RenderInput load_render_input(const std::string& input, const scene::LoadOptions& load,
                              const scene::NumberFormat& format) {
  if (ends_with(input, ".rcimg")) {
    scene::SceneImage img = scene::SceneImage::load(input);
    return {input, std::nullopt, std::move(img), std::nullopt, std::nullopt};
  }
  scene::Scene s = scene::load_scene(input, load);
  scene::CompileOptions opt;
  opt.format = format;
  scene::Compiled c = scene::compile_scene(s, opt);
  scene::SceneImage img = scene::SceneImage::from_bytes(std::move(c.image), input);
  std::optional<scene::Camera> camera = s.camera;
  return {input, std::move(s), std::move(img), std::move(c.stats), std::move(camera)};
}

void require_valid(const scene::SceneImage& image) {
  const scene::Validation v = image.validation(4);
  if (v.ok()) return;
  std::string text;
  for (const std::string& p : v.problems) text += "\n  " + p;
  if (v.total > v.problems.size())
    text += "\n  ... and " + std::to_string(v.total - v.problems.size()) +
            " more (`raycore scene info` lists them)";
  throw scene::Error(image.name() + ": the image is malformed (" + std::to_string(v.total) +
                     (v.total == 1 ? " problem):" : " problems):") + text);
}

Camera auto_camera_for(const scene::SceneImage& img) {
  const auto b = img.bounds();
  return scene::auto_camera(glm::dvec3(b[0], b[1], b[2]), glm::dvec3(b[3], b[4], b[5]));
}

RenderOptions input_options(const RenderInput& in) {
  RenderOptions o;
  const scene::ViewRecord v = in.image.view();
  o.width = v.width ? v.width : o.width;
  o.height = v.height ? v.height : o.height;
  for (int c = 0; c < 3; ++c) o.background[c] = to_byte(v.background[c]);
  if (v.flags & spec::kImageViewFlagAutoCamera) {
    o.camera = auto_camera_for(in.image);
  } else if (in.camera) {  // the scene's camera in double
    o.camera.eye = in.camera->eye;
    o.camera.look = in.camera->look;
    o.camera.up = in.camera->up;
    o.camera.fov_deg = in.camera->fov_deg;
  } else {  // an image file: its view record in float32
    o.camera.eye = glm::dvec3(v.eye[0], v.eye[1], v.eye[2]);
    o.camera.look = glm::dvec3(v.look[0], v.look[1], v.look[2]);
    o.camera.up = glm::dvec3(v.up[0], v.up[1], v.up[2]);
    o.camera.fov_deg = v.fov_deg;
  }
  return o;
}

}  // namespace rc
