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
};

// Traces every pixel's ray (from the shared ray generator, rounded to the core's format T as the
// core sees it, then widened to float32 exactly) with Embree; shades hits with the headlight model
// in double. Frame.counters.rays is set; the other counters stay zero.
template <class T>
Frame render_embree(const std::vector<SoupTriangle>& tris, const RenderOptions& opt);

// Headlight shading in double (the reference for PSNR): Kd * (ambient + (1 - ambient) * |cos|).
std::array<uint8_t, 3> shade_double(const SoupTriangle& tri, const glm::dvec3& dir);

}  // namespace rc
