// Camera and primary-ray generation (docs/architecture.md, "Rays"). The same code generates the
// rays for the golden model, the Embree reference and the RTL harness.
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <string>

#include "scene.hpp"

namespace rc {

// The scene's camera type (eye, look, up, vertical fov in degrees); scene::auto_camera() places
// the automatic one.
using Camera = scene::Camera;

// Parses "eye=X,Y,Z:look=X,Y,Z:up=X,Y,Z:fov=DEG" (every part optional but eye and look, none
// twice; every number a whole decimal number, no trailing text), then validate_camera().
// Throws std::runtime_error naming the problem.
Camera parse_camera(const std::string& text);

// Checks the camera with the project's one camera rule, scene::check_camera() (tb/scene/scene.hpp:
// finite float32 coordinates, eye != look, up not zero and not nearly parallel to the view
// direction, fov in [0.001, 179.999] degrees), the rule `scene build` applies to scene files;
// throws rc::scene::Error ("camera.FIELD: ...") naming the problem.
void validate_camera(const Camera& cam);

// One primary ray in double precision, before rounding to the core's format: origin, direction
// d(x, y) = f + ((x+0.5)/W*2 - 1)*h*a*r + (1 - (y+0.5)/H*2)*h*u, and 1/|d| (used by shading).
struct RayD {
  glm::dvec3 org;
  glm::dvec3 dir;
  double inv_len;
};

// The ray generation unit's camera registers (docs/architecture.md, "Two ray sources"), in
// double before rounding to the format: the origin, the direction through pixel (0, 0) and the
// direction steps of one pixel right and one pixel down.
struct CameraRegistersD {
  glm::dvec3 eye, c0, cx, cy;
};
CameraRegistersD camera_registers(const Camera& cam, uint32_t width, uint32_t height);

class RayGenerator {
 public:
  RayGenerator(const Camera& cam, uint32_t width, uint32_t height);
  RayD ray(uint32_t x, uint32_t y) const;
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  glm::dvec3 eye_, f_, r_, u_;
  double h_, a_;
  uint32_t width_, height_;
};

}  // namespace rc
