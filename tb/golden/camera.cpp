#include "camera.hpp"

#include <cctype>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <vector>

namespace rc {

namespace {

// The parts of `text` between separators, empty ones included ("1,2," has three parts).
std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const size_t end = text.find(sep, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

// One number of the --camera text: the whole item must be a number (no blanks, no trailing text).
double parse_number(const std::string& key, const std::string& item) {
  size_t used = 0;
  double v = 0.0;
  try {
    if (item.empty() || std::isspace(static_cast<unsigned char>(item[0])))
      throw std::invalid_argument(item);
    v = std::stod(item, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != item.size())
    throw std::runtime_error("camera: " + key + " has a bad number '" + item + "'");
  return v;
}

glm::dvec3 parse_vec(const std::string& key, const std::string& value) {
  const std::vector<std::string> parts = split(value, ',');
  if (parts.size() != 3)
    throw std::runtime_error("camera: " + key + " needs three numbers X,Y,Z, got '" + value + "'");
  return {parse_number(key, parts[0]), parse_number(key, parts[1]), parse_number(key, parts[2])};
}

}  // namespace

Camera parse_camera(const std::string& text) {
  Camera cam;
  bool have_eye = false, have_look = false, have_up = false, have_fov = false;
  const auto once = [](bool* seen, const std::string& key) {
    if (*seen) throw std::runtime_error("camera: " + key + " is given twice");
    *seen = true;
  };
  for (const std::string& part : split(text, ':')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos)
      throw std::runtime_error("camera: expected key=value, got '" + part + "'");
    const std::string key = part.substr(0, eq), value = part.substr(eq + 1);
    if (key == "eye") {
      once(&have_eye, key);
      cam.eye = parse_vec(key, value);
    } else if (key == "look") {
      once(&have_look, key);
      cam.look = parse_vec(key, value);
    } else if (key == "up") {
      once(&have_up, key);
      cam.up = parse_vec(key, value);
    } else if (key == "fov") {
      once(&have_fov, key);
      cam.fov_deg = parse_number(key, value);
    } else {
      throw std::runtime_error("camera: unknown key '" + key + "' (eye, look, up, fov)");
    }
  }
  if (!have_eye || !have_look) throw std::runtime_error("camera: eye= and look= are required");
  validate_camera(cam);
  return cam;
}

void validate_camera(const Camera& cam) { scene::check_camera(cam, "camera"); }

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
