// Where the tests find the shared test models (bunny, Sponza, the conference room, ...): the first
// directory of RAYCORE_MODELS_PATH (':' separates several; the scene loader searches the same
// variable, tb/scene/scene.hpp) that exists, else ../shared/models beside the repository. Empty
// when none exists: the tests that need the models then skip, and `make test` fails on any skip
// unless RAYCORE_ALLOW_SKIPS=1 (README, "Test models").
#pragma once

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#ifndef RC_SOURCE_DIR
#error "RC_SOURCE_DIR must name the repository root"
#endif

namespace rc::test {

inline std::string shared_models_dir() {
  if (const char* env = std::getenv("RAYCORE_MODELS_PATH")) {
    std::stringstream ss(env);
    std::string dir;
    while (std::getline(ss, dir, ':'))
      if (!dir.empty() && std::filesystem::is_directory(dir)) return dir;
  }
  const std::string dir = std::string(RC_SOURCE_DIR) + "/../shared/models";
  return std::filesystem::is_directory(dir) ? dir : std::string();
}

}  // namespace rc::test
