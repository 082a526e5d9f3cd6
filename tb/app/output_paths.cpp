#include "output_paths.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "error.hpp"

namespace rc::app {

namespace fs = std::filesystem;
using rc::scene::Error;

namespace {

std::string normal_path(const std::string& p) {
  std::error_code ec;
  fs::path abs = fs::absolute(p, ec);
  if (ec) return p;
  fs::path canon = fs::weakly_canonical(abs, ec);
  return (ec ? abs.lexically_normal() : canon).string();
}

void check_writable(const NamedPath& out) {
  const auto fail = [&](const std::string& why) {
    throw Error(out.option + " " + out.path + ": cannot write: " + why);
  };
  struct stat st {};
  if (::stat(out.path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) fail("it is a directory");
    if (::access(out.path.c_str(), W_OK) != 0) fail(std::strerror(errno));
    return;
  }
  if (errno != ENOENT) fail(std::strerror(errno));
  fs::path dir = fs::path(out.path).parent_path();
  if (dir.empty()) dir = ".";
  if (::stat(dir.c_str(), &st) != 0)
    fail("the directory " + dir.string() + " does not exist (" + std::strerror(errno) + ")");
  if (!S_ISDIR(st.st_mode)) fail(dir.string() + " is not a directory");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    fail("the directory " + dir.string() + " is not writable (" + std::strerror(errno) + ")");
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  return normal_path(a) == normal_path(b);
}

void check_output_dir(const NamedPath& dir) {
  const auto fail = [&](const std::string& why) {
    throw Error(dir.option + " " + dir.path + ": cannot write into it: " + why);
  };
  if (dir.path.empty()) fail("empty path");
  fs::path p = fs::absolute(dir.path).lexically_normal();
  struct stat st {};
  bool exists = ::stat(p.c_str(), &st) == 0;
  if (exists && !S_ISDIR(st.st_mode)) fail("it exists and is not a directory");
  while (!exists && p.has_parent_path() && p != p.parent_path()) {  // the nearest existing parent
    p = p.parent_path();
    exists = ::stat(p.c_str(), &st) == 0;
  }
  if (!exists) fail("no part of it exists");
  if (!S_ISDIR(st.st_mode)) fail(p.string() + " is not a directory");
  if (::access(p.c_str(), W_OK | X_OK) != 0)
    fail("the directory " + p.string() + " is not writable (" + std::strerror(errno) + ")");
}

std::vector<NamedPath> scene_inputs(const rc::scene::Scene& scene) {
  std::vector<NamedPath> in;
  const auto file = [](const std::string& s) { return s.rfind("builtin:", 0) != 0; };
  if (file(scene.source)) in.push_back({"input", scene.source});
  for (const auto& m : scene.meshes) {
    if (file(m.source) && m.source != scene.source) in.push_back({"mesh", m.source});
    for (const auto& mtl : m.material_files) in.push_back({"MTL file", mtl});
  }
  return in;
}

void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& o = outputs[i];
    if (o.path.empty()) continue;
    check_writable(o);
    for (const NamedPath& in : inputs)
      if (!in.path.empty() && same_file(o.path, in.path))
        throw Error(o.option + " " + o.path + ": is the " + in.option + " " + in.path +
                    ": refusing to overwrite an input");
    for (size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && same_file(o.path, outputs[j].path))
        throw Error(o.option + " " + o.path + " and " + outputs[j].option + " " + outputs[j].path +
                    " are the same file: give each output its own path");
  }
}

}  // namespace rc::app
