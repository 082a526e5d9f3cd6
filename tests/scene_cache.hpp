// The RTL tests' scene inputs, compiled once per ctest run instead of once per test process.
//
// Each ctest test is a process of its own, and a case on the conference room or Sponza spent more
// time loading and compiling its scene (2 to 5 s) than simulating it. ctest gives the tests that
// use this cache a directory in RC_TEST_SCENE_CACHE (tests/CMakeLists.txt: the fixture test
// SceneCache.Clear empties it before them, SceneCache.Remove deletes it after them, so no image
// outlives the build that compiled it). The first process that needs an input compiles it, as
// load_render_input() does, and writes the image (<dir>/<input>.rcimg, every character other than
// a letter or digit as '_') and the scene's camera (.camera, the doubles in hexadecimal: exact);
// the others read both. Each file is written under a temporary name and renamed, the camera
// before the image, so a reader that finds the image finds a whole image and its camera.
// Without RC_TEST_SCENE_CACHE (a test binary run by hand) every call compiles.
#pragma once

#include <unistd.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "job.hpp"

namespace rc::test {

// A camera's ten doubles: eye, look, up, fov_deg (the order of the .camera file).
inline std::array<double, 10> camera_values(const scene::Camera& c) {
  return {c.eye.x,  c.eye.y, c.eye.z, c.look.x, c.look.y,
          c.look.z, c.up.x,  c.up.y,  c.up.z,   c.fov_deg};
}

namespace scene_cache_detail {

inline void write_atomically(const std::filesystem::path& path, const std::string& bytes) {
  const std::filesystem::path tmp =
      path.string() + ".tmp" + std::to_string(static_cast<long>(::getpid()));
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!f) throw std::runtime_error("scene cache: cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, path);
}

inline std::string read_all(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("scene cache: cannot read " + path.string());
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// "none", or the ten doubles eye, look, up, fov_deg in %a form (exact in both directions).
inline std::string camera_text(const std::optional<scene::Camera>& cam) {
  if (!cam) return "none\n";
  std::string s;
  char buf[64];
  for (double d : camera_values(*cam)) {
    std::snprintf(buf, sizeof buf, "%a\n", d);
    s += buf;
  }
  return s;
}

inline std::optional<scene::Camera> parse_camera(const std::string& text, const std::string& path) {
  if (text == "none\n") return std::nullopt;
  std::istringstream in(text);
  double v[10];
  for (double& d : v) {
    std::string word;
    char* end = nullptr;
    if (in >> word) d = std::strtod(word.c_str(), &end);
    if (end == nullptr || end == word.c_str() || *end != '\0')
      throw std::runtime_error("scene cache: " + path + " is not a camera file");
  }
  scene::Camera cam;
  cam.eye = {v[0], v[1], v[2]};
  cam.look = {v[3], v[4], v[5]};
  cam.up = {v[6], v[7], v[8]};
  cam.fov_deg = v[9];
  return cam;
}

}  // namespace scene_cache_detail

// load_render_input(input, LoadOptions{}, fp24), through the cache when ctest set one up. The
// result has the compiled image (read through SceneImage::load(), so its checks run and it is
// named by its cache file) and the scene's camera, and neither the scene itself nor the build
// statistics (a test that needs those calls load_render_input()).
inline RenderInput cached_render_input(const std::string& input) {
  namespace fs = std::filesystem;
  namespace d = scene_cache_detail;
  const char* dir = std::getenv("RC_TEST_SCENE_CACHE");
  if (dir == nullptr || *dir == '\0') {
    RenderInput in = load_render_input(input, scene::LoadOptions{}, scene::NumberFormat::fp24());
    in.scene.reset();
    in.build.reset();
    return in;
  }
  std::string stem = input;
  for (char& ch : stem)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  const fs::path image_path = fs::path(dir) / (stem + ".rcimg");
  const fs::path camera_path = fs::path(dir) / (stem + ".camera");
  if (!fs::exists(image_path)) {
    const RenderInput in =
        load_render_input(input, scene::LoadOptions{}, scene::NumberFormat::fp24());
    fs::create_directories(dir);
    d::write_atomically(camera_path, d::camera_text(in.camera));
    const std::vector<uint8_t>& bytes = in.image.bytes();
    d::write_atomically(image_path, std::string(bytes.begin(), bytes.end()));
  }
  return RenderInput{input, std::nullopt, scene::SceneImage::load(image_path.string()),
                     std::nullopt, d::parse_camera(d::read_all(camera_path), camera_path.string())};
}

}  // namespace rc::test
