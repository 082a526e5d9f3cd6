// The outside reference: the same primary rays traced by Embree 3 in float32, shaded in double.
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "render.hpp"

namespace rc {

// Geometry for the reference engines: triangle i (OBJ order after fan triangulation) with its
// vertices and diffuse colour. Dropped (degenerate) triangles may be present; Embree ignores them.
struct SoupTriangle {
  std::array<glm::dvec3, 3> v;
  std::array<double, 3> kd;
  std::array<double, 3> ks{0.0, 0.0, 0.0};
  double ns = 0.0;
  double mirror = 0.0;    // mirror reflection weight (docs/memory-format.md, materials)
  double transmit = 0.0;  // refraction weight
  double ior = 1.0;       // index of refraction (Ni)
};

// A scene light for the reference: a point light's position, or the unit vector toward a
// directional light; its colour times its intensity.
struct SoupLight {
  bool directional = false;
  glm::dvec3 pos{0.0, 0.0, 0.0};
  glm::dvec3 color{1.0, 1.0, 1.0};
};

// Traces every pixel's ray (from the shared ray generator, rounded to the core's format T as the
// core sees it, then widened to float32 exactly) with Embree; shades hits in double: with the
// headlight model, or with opt.lighting == kScene and lights, by the lighting rules
// (docs/architecture.md, "Lighting", "Reflection" and "Refraction") with Embree's occlusion test
// for the shadow rays and its closest hit for the mirror and refraction rays (from the hit point,
// float32, beyond t_eps, the start triangle excluded), to opt.max_bounces. Frame.counters.rays is
// set; the other counters stay zero.
template <class T>
Frame render_embree(const std::vector<SoupTriangle>& tris, const RenderOptions& opt,
                    const std::vector<SoupLight>& lights = {});

// Headlight shading in double (the reference for PSNR): Kd * (ambient + (1 - ambient) * |cos|).
std::array<uint8_t, 3> shade_double(const SoupTriangle& tri, const glm::dvec3& dir);

}  // namespace rc
