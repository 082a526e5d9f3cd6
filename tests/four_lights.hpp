// A lit test scene with the hardware's most lights (spec::kLightMaxLights, 4): the scene's own
// light and three more, point and directional, coloured. The tracer's (tracer_rtl_test) and the
// lit board's (board_rtl_test) cases light a scene with it.
#pragma once

#include <optional>

#include "compiler.hpp"
#include "job.hpp"

namespace rc::test {

// `in` (a scene file's input, with its scene) with three more lights, compiled again.
inline RenderInput with_four_lights(const RenderInput& in) {
  scene::Scene s = *in.scene;
  scene::Light a, b, d;
  a.position = {-0.6, 1.2, 0.5};
  a.color = {1.0, 0.6, 0.3};
  a.intensity = 0.7;
  b.type = scene::Light::Type::kDirectional;
  b.position = {0.3, -1.0, -0.4};
  b.color = {0.4, 0.5, 1.0};
  b.intensity = 0.5;
  d.position = {0.7, 0.3, 0.8};
  d.intensity = 0.3;
  s.lights.push_back(a);
  s.lights.push_back(b);
  s.lights.push_back(d);
  const scene::Compiled cc = scene::compile_scene(s, scene::CompileOptions{});
  return RenderInput{s.name, s, scene::SceneImage::from_bytes(cc.image, s.name), std::nullopt,
                     s.camera};
}

}  // namespace rc::test
