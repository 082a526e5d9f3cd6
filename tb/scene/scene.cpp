#include "scene.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "error.hpp"
#include "procedural.hpp"

#ifndef RC_SOURCE_DIR
#define RC_SOURCE_DIR "."
#endif

namespace rc::scene {
namespace {

using nlohmann::json;

bool is_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string join(const std::string& dir, const std::string& path) {
  if (dir.empty()) return path;
  return dir.back() == '/' ? dir + path : dir + "/" + path;
}

std::string parent_dir(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string stem(const std::string& path) {
  const auto slash = path.find_last_of('/');
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  const auto dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

void split_path_list(const std::string& list, std::vector<std::string>* out) {
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ':'))
    if (!item.empty()) out->push_back(item);
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string num(double v) {
  std::ostringstream ss;
  ss << std::setprecision(9) << v;
  return ss.str();
}

// Why a coordinate cannot be stored as float32 (the view and light records), or "".
std::string f32_problem(double x, char axis) {
  const std::string what = std::string(1, axis) + " = " + num(x);
  if (!std::isfinite(x)) return what + " is not a finite number";
  if (std::abs(x) > static_cast<double>(std::numeric_limits<float>::max()))
    return what + " is outside the float32 range (|x| <= " +
           num(static_cast<double>(std::numeric_limits<float>::max())) +
           "; the image stores it as float32)";
  return "";
}

// v rounded to float32, as the view and light records store it. The floats go through a volatile:
// GCC 12.2's SLP vectorizer (-O2 and -O3) drops the double -> float -> double round trip of the
// plain expression inlined into camera_problem(), which then never sees the rounded camera.
glm::dvec3 to_f32(const glm::dvec3& v) {
  const volatile float f[3] = {static_cast<float>(v.x), static_cast<float>(v.y),
                               static_cast<float>(v.z)};
  return glm::dvec3(f[0], f[1], f[2]);
}

// The direction of v, computed without overflow or underflow for any finite v (zero for zero).
glm::dvec3 direction(const glm::dvec3& v) {
  const double m = std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
  if (m == 0.0) return glm::dvec3(0.0);
  return glm::normalize(v / m);
}

// Strict JSON field access: every problem names the file and the field.
class Fields {
 public:
  Fields(const json& obj, std::string where, std::string file)
      : obj_(obj), where_(std::move(where)), file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const std::string path = where_ + (where_.empty() || key.empty() ? "" : ".") + key;
    throw Error(file_ + ": " + (path.empty() ? "" : path + ": ") + what);
  }
  void expect_object() const {
    if (!obj_.is_object()) fail("", "expected a JSON object");
  }
  void only(std::initializer_list<const char*> keys) const {
    expect_object();
    for (const auto& item : obj_.items()) {
      bool known = false;
      for (const char* k : keys) known = known || item.key() == k;
      if (!known) fail(item.key(), "unknown key");
    }
  }
  bool has(const char* key) const { return obj_.contains(key); }
  // The value of a key; a missing key (or a value that is not an object) is an Error naming the
  // file and the key's path, never nlohmann's own exception.
  const json& at(const char* key) const {
    expect_object();
    const auto it = obj_.find(key);
    if (it == obj_.end()) fail(key, "missing (this key is required)");
    return *it;
  }
  double number(const char* key) const {
    const json& v = at(key);
    if (!v.is_number()) fail(key, "expected a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(key, "expected a finite number");
    return d;
  }
  std::string string(const char* key) const {
    const json& v = at(key);
    if (!v.is_string()) fail(key, "expected a string");
    return v.get<std::string>();
  }
  glm::dvec3 vec3(const char* key) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
        !v[2].is_number())
      fail(key, "expected an array of 3 numbers");
    const glm::dvec3 r(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z))
      fail(key, "expected finite numbers");
    return r;
  }
  // A vec3 the image stores as float32: finite and inside the float32 range.
  glm::dvec3 vec3_f32(const char* key) const {
    const glm::dvec3 r = vec3(key);
    for (int k = 0; k < 3; ++k)
      if (const std::string why = f32_problem(r[k], "xyz"[k]); !why.empty()) fail(key, why);
    return r;
  }
  // A colour: three numbers in [0, kMaxColour].
  glm::dvec3 colour(const char* key) const {
    const glm::dvec3 r = vec3(key);
    for (int k = 0; k < 3; ++k)
      if (!(r[k] >= 0.0 && r[k] <= kMaxColour))
        fail(key, std::string(1, "rgb"[k]) + " = " + num(r[k]) + " is outside [0, " +
                      num(kMaxColour) + "] (colours are fractions per channel, 1 = 255)");
    return r;
  }
  std::string sub(const std::string& key) const {
    return where_.empty() ? key : where_ + "." + key;
  }
  const std::string& file() const { return file_; }

 private:
  const json& obj_;
  std::string where_;
  std::string file_;
};

glm::dmat4 parse_transform(const Fields& f) {
  f.only({"scale", "rotate", "translate"});
  glm::dmat4 m(1.0);
  if (f.has("translate")) m = glm::translate(m, f.vec3("translate"));
  if (f.has("rotate")) {
    // Degrees about x, then y, then z (applied to the mesh in that order).
    const glm::dvec3 r = glm::radians(f.vec3("rotate"));
    m = glm::rotate(m, r.z, glm::dvec3(0, 0, 1));
    m = glm::rotate(m, r.y, glm::dvec3(0, 1, 0));
    m = glm::rotate(m, r.x, glm::dvec3(1, 0, 0));
  }
  if (f.has("scale")) {
    const json& s = f.at("scale");
    const glm::dvec3 v = s.is_number() ? glm::dvec3(f.number("scale")) : f.vec3("scale");
    if (v.x == 0.0 || v.y == 0.0 || v.z == 0.0) f.fail("scale", "must not be zero");
    m = glm::scale(m, v);
  }
  return m;
}

Mesh load_mesh_entry(const Fields& f, const std::string& base_dir, const LoadOptions& options) {
  f.only({"path", "builtin", "params", "transform"});
  Mesh mesh;
  if (f.has("path") == f.has("builtin")) f.fail("", "give exactly one of 'path' and 'builtin'");
  if (f.has("path")) {
    if (f.has("params")) f.fail("params", "only built-in meshes take parameters");
    mesh = load_obj(find_model(f.string("path"), base_dir, options));
  } else {
    mesh = builtin_mesh(f.string("builtin"), f.has("params") ? f.at("params") : json::object());
  }
  if (f.has("transform")) {
    const glm::dmat4 m = parse_transform(Fields(f.at("transform"), f.sub("transform"), f.file()));
    for (auto& v : mesh.vertices) v = glm::dvec3(m * glm::dvec4(v, 1.0));
  }
  return mesh;
}

}  // namespace

std::string source_root() { return RC_SOURCE_DIR; }

std::vector<std::string> model_search_path(const LoadOptions& options) {
  std::vector<std::string> dirs;
  for (const auto& p : options.models_path) split_path_list(p, &dirs);
  if (const char* env = std::getenv("RAYCORE_MODELS_PATH")) split_path_list(env, &dirs);
  dirs.push_back("../shared/models");
  dirs.push_back(join(source_root(), "../shared/models"));
  return dirs;
}

std::string find_model(const std::string& path, const std::string& base_dir,
                       const LoadOptions& options) {
  if (path.empty()) throw Error("empty mesh path");
  std::vector<std::string> tried;
  const auto attempt = [&](const std::string& candidate) {
    tried.push_back(candidate);
    return is_file(candidate);
  };
  if (path[0] == '/') {
    if (attempt(path)) return path;
  } else {
    const std::string first = base_dir.empty() ? path : join(base_dir, path);
    if (attempt(first)) return first;
    for (const auto& dir : model_search_path(options))
      if (attempt(join(dir, path))) return join(dir, path);
  }
  std::string list;
  for (const auto& t : tried) list += "\n  " + t;
  throw Error(path + ": mesh file not found; looked at:" + list +
              "\n(set --models-path or RAYCORE_MODELS_PATH)");
}

std::optional<CameraProblem> camera_problem(const Camera& cam) {
  const std::pair<const char*, const glm::dvec3*> vectors[] = {
      {"eye", &cam.eye}, {"look", &cam.look}, {"up", &cam.up}};
  for (const auto& [field, v] : vectors)
    for (int k = 0; k < 3; ++k)
      if (std::string why = f32_problem((*v)[k], "xyz"[k]); !why.empty())
        return CameraProblem{field, std::move(why)};
  if (!(cam.fov_deg >= kMinFovDeg && cam.fov_deg <= kMaxFovDeg))
    return CameraProblem{"fov", num(cam.fov_deg) + " degrees is outside [" + num(kMinFovDeg) +
                                    ", " + num(kMaxFovDeg) +
                                    "] (the vertical field of view, in degrees)"};
  // The view in double, then as the image's view record holds it (float32).
  for (int pass = 0; pass < 2; ++pass) {
    const glm::dvec3 eye = pass == 0 ? cam.eye : to_f32(cam.eye);
    const glm::dvec3 look = pass == 0 ? cam.look : to_f32(cam.look);
    const glm::dvec3 up = pass == 0 ? cam.up : to_f32(cam.up);
    const std::string as = pass == 0 ? "" : " once rounded to float32 (the image stores float32)";
    if (look == eye) return CameraProblem{"look", "must differ from eye" + as};
    if (up == glm::dvec3(0.0)) return CameraProblem{"up", "must not be zero" + as};
    const double sine = glm::length(glm::cross(direction(look - eye), direction(up)));
    if (!(sine >= kMinUpSine))
      return CameraProblem{"up", "is parallel to the view direction" + as +
                                     ": the sine of the angle between them is " + num(sine) +
                                     ", it must be at least " + num(kMinUpSine)};
  }
  return std::nullopt;
}

void check_camera(const Camera& cam, const std::string& where) {
  if (const auto problem = camera_problem(cam))
    throw Error(where + "." + problem->field + ": " + problem->what);
}

Camera auto_camera(const glm::dvec3& lo, const glm::dvec3& hi) {
  Camera cam;
  cam.fov_deg = 45.0;
  cam.look = (lo + hi) * 0.5;
  cam.eye = cam.look + glm::normalize(glm::dvec3(0.3, 0.25, 1.0)) * (1.6 * glm::length(hi - lo));
  cam.up = {0.0, 1.0, 0.0};
  return cam;
}

Scene load_scene_json_text(const std::string& text, const std::string& name,
                           const std::string& base_dir, const LoadOptions& options) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {  // parse errors, and numbers too large for a double
    throw Error(name + ": invalid JSON: " + e.what());
  }
  const Fields top(doc, "", name);
  top.only({"name", "description", "meshes", "camera", "resolution", "background", "lights"});
  Scene scene;
  scene.source = name;
  scene.name = top.has("name") ? top.string("name") : stem(name);
  if (top.has("description")) (void)top.string("description");
  if (!top.has("meshes") || !top.at("meshes").is_array() || top.at("meshes").empty())
    top.fail("meshes", "expected a non-empty array of meshes");
  const json& meshes = top.at("meshes");
  for (size_t i = 0; i < meshes.size(); ++i) {
    const Fields mf(meshes[i], "meshes[" + std::to_string(i) + "]", name);
    mf.expect_object();
    scene.meshes.push_back(load_mesh_entry(mf, base_dir, options));
  }
  if (top.has("camera")) {
    const Fields cf(top.at("camera"), "camera", name);
    cf.only({"eye", "look", "up", "fov"});
    Camera cam;
    cam.eye = cf.vec3("eye");
    cam.look = cf.vec3("look");
    if (cf.has("up")) cam.up = cf.vec3("up");
    if (cf.has("fov")) cam.fov_deg = cf.number("fov");
    if (const auto problem = camera_problem(cam)) cf.fail(problem->field, problem->what);
    scene.camera = cam;
  }
  if (top.has("resolution")) {
    const json& r = top.at("resolution");
    if (!r.is_array() || r.size() != 2 || !r[0].is_number_integer() || !r[1].is_number_integer() ||
        r[0].get<int64_t>() < 1 || r[1].get<int64_t>() < 1 || r[0].get<int64_t>() > 16384 ||
        r[1].get<int64_t>() > 16384)
      top.fail("resolution", "expected [width, height], integers in 1..16384");
    scene.width = r[0].get<uint32_t>();
    scene.height = r[1].get<uint32_t>();
  }
  if (top.has("background")) scene.background = top.colour("background");
  if (top.has("lights")) {
    const json& lights = top.at("lights");
    if (!lights.is_array()) top.fail("lights", "expected an array");
    for (size_t i = 0; i < lights.size(); ++i) {
      const Fields lf(lights[i], "lights[" + std::to_string(i) + "]", name);
      lf.only({"type", "position", "direction", "color", "intensity"});
      Light light;
      const std::string type = lf.has("type") ? lf.string("type") : "point";
      if (type == "point") {
        light.type = Light::Type::kPoint;
        if (!lf.has("position")) lf.fail("position", "a point light needs a position");
        if (lf.has("direction")) lf.fail("direction", "a point light has no direction");
        light.position = lf.vec3_f32("position");
      } else if (type == "directional") {
        light.type = Light::Type::kDirectional;
        if (!lf.has("direction")) lf.fail("direction", "a directional light needs a direction");
        if (lf.has("position")) lf.fail("position", "a directional light has no position");
        light.position = lf.vec3_f32("direction");
        if (to_f32(light.position) == glm::dvec3(0.0))
          lf.fail("direction", "must not be zero (as float32, as the image stores it)");
      } else {
        lf.fail("type", "expected \"point\" or \"directional\"");
      }
      if (lf.has("color")) light.color = lf.colour("color");
      if (lf.has("intensity")) {
        light.intensity = lf.number("intensity");
        if (!(light.intensity >= 0.0 && light.intensity <= kMaxIntensity))
          lf.fail("intensity",
                  num(light.intensity) + " is outside [0, " + num(kMaxIntensity) + "]");
      }
      scene.lights.push_back(light);
    }
  }
  return scene;
}

Scene load_scene(const std::string& input, const LoadOptions& options) {
  const std::string prefix = "builtin:";
  if (input.compare(0, prefix.size(), prefix) == 0)
    return builtin_scene(input.substr(prefix.size()));
  if (ends_with(input, ".json")) {
    std::ifstream in(input, std::ios::binary);
    if (!in) throw Error(input + ": cannot open scene file: " + std::strerror(errno));
    if (!is_file(input)) throw Error(input + ": cannot open scene file: not a regular file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return load_scene_json_text(ss.str(), input, parent_dir(input), options);
  }
  Scene scene;
  const std::string path = find_model(input, "", options);
  scene.source = path;
  scene.name = stem(path);
  scene.meshes.push_back(load_obj(path));
  return scene;
}

}  // namespace rc::scene
