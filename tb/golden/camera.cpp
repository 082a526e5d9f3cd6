#include "camera.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rc {

namespace {

glm::dvec3 parse_vec(const std::string& key, const std::string& value) {
  std::vector<double> parts;
  std::stringstream ss(value);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      size_t used = 0;
      parts.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw std::runtime_error("camera: " + key + " has a bad number '" + item + "'");
    }
  }
  if (parts.size() != 3)
    throw std::runtime_error("camera: " + key + " needs three numbers X,Y,Z, got '" + value + "'");
  return {parts[0], parts[1], parts[2]};
}

}  // namespace

Camera parse_camera(const std::string& text) {
  Camera cam;
  bool have_eye = false, have_look = false;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ':')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos)
      throw std::runtime_error("camera: expected key=value, got '" + part + "'");
    const std::string key = part.substr(0, eq), value = part.substr(eq + 1);
    if (key == "eye") {
      cam.eye = parse_vec(key, value);
      have_eye = true;
    } else if (key == "look") {
      cam.look = parse_vec(key, value);
      have_look = true;
    } else if (key == "up") {
      cam.up = parse_vec(key, value);
    } else if (key == "fov") {
      try {
        cam.fov_deg = std::stod(value);
      } catch (const std::exception&) {
        throw std::runtime_error("camera: fov has a bad number '" + value + "'");
      }
    } else {
      throw std::runtime_error("camera: unknown key '" + key + "' (eye, look, up, fov)");
    }
  }
  if (!have_eye || !have_look) throw std::runtime_error("camera: eye= and look= are required");
  validate_camera(cam);
  return cam;
}

void validate_camera(const Camera& cam) {
  for (const auto* v : {&cam.eye, &cam.look, &cam.up})
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite((*v)[i])) throw std::runtime_error("camera: coordinates must be finite");
  const glm::dvec3 f = cam.look - cam.eye;
  if (glm::length(f) == 0.0) throw std::runtime_error("camera: eye and look are the same point");
  if (glm::length(glm::cross(glm::normalize(f), cam.up)) < 1e-9)
    throw std::runtime_error("camera: up is parallel to the view direction (or zero)");
  if (!(cam.fov_deg > 0.0 && cam.fov_deg < 180.0))
    throw std::runtime_error("camera: fov must be between 0 and 180 degrees");
}

RayGenerator::RayGenerator(const Camera& cam, uint32_t width, uint32_t height)
    : width_(width), height_(height) {
  validate_camera(cam);
  if (width == 0 || height == 0) throw std::runtime_error("image size must be at least 1x1");
  eye_ = cam.eye;
  f_ = glm::normalize(cam.look - cam.eye);
  r_ = glm::normalize(glm::cross(f_, cam.up));
  u_ = glm::cross(r_, f_);
  h_ = std::tan(cam.fov_deg * M_PI / 360.0);
  a_ = static_cast<double>(width) / static_cast<double>(height);
}

CameraRegistersD camera_registers(const Camera& cam, uint32_t width, uint32_t height) {
  validate_camera(cam);
  if (width == 0 || height == 0) throw std::runtime_error("image size must be at least 1x1");
  const glm::dvec3 f = glm::normalize(cam.look - cam.eye);
  const glm::dvec3 r = glm::normalize(glm::cross(f, cam.up));
  const glm::dvec3 u = glm::cross(r, f);
  const double h = std::tan(cam.fov_deg * M_PI / 360.0);
  const double w = static_cast<double>(width), ht = static_cast<double>(height);
  const double a = w / ht;
  CameraRegistersD c;
  c.eye = cam.eye;
  c.c0 = f + (1.0 / w - 1.0) * h * a * r + (1.0 - 1.0 / ht) * h * u;
  c.cx = (2.0 * h * a / w) * r;
  c.cy = -(2.0 * h / ht) * u;
  return c;
}

RayD RayGenerator::ray(uint32_t x, uint32_t y) const {
  const double sx = (static_cast<double>(x) + 0.5) / width_ * 2.0 - 1.0;
  const double sy = 1.0 - (static_cast<double>(y) + 0.5) / height_ * 2.0;
  const glm::dvec3 d = f_ + sx * h_ * a_ * r_ + sy * h_ * u_;
  return {eye_, d, 1.0 / glm::length(d)};
}

}  // namespace rc
