// Verilated models built as modules: shared libraries loaded when a run asks for them, so that
// building `raycore` (what `make render` needs) compiles only the default core model. The core
// with Threads = 1 (rc_core_t1), with IsectInterval = 1 (rc_core_i1) and the board build
// (rc_board_model) are modules; `make` and `make test` build them (tb/harness/CMakeLists.txt).
//
// A module exports one extern "C" function that runs a whole simulation and reports an exception
// as a status and a message (ModuleStatus), which the caller throws again as the same type: no
// exception crosses the module's boundary. A module links its own copy of the harness and of
// Verilator's runtime; only plain data (the image, options and results) is passed between them.
#pragma once

#include <exception>
#include <stdexcept>
#include <string>

#include "error.hpp"

namespace rc::harness {

// How a module's entry point ended.
enum ModuleStatus : int {
  kModuleOk = 0,
  kModuleSimError = 1,    // CoreSimError or BoardSimError: the run failed
  kModuleSceneError = 2,  // scene::Error: the image or frame cannot be used
  kModuleOtherError = 3,  // any other exception
};

// The address of `symbol` in the module `name` (the library lib<name>.so in the build's module
// directory), loading it once. Throws scene::Error naming the module and how to build it when it
// cannot be loaded.
void* module_symbol(const std::string& name, const char* symbol);

// A module's entry point runs its work through this: kModuleOk, or the status of the exception
// the work threw (SimError: the run failed) with its message in *error.
template <class SimError, class Work>
int run_in_module(std::string* error, Work&& work) {
  try {
    work();
    return kModuleOk;
  } catch (const SimError& e) {
    *error = e.what();
    return kModuleSimError;
  } catch (const scene::Error& e) {
    *error = e.what();
    return kModuleSceneError;
  } catch (const std::exception& e) {
    *error = e.what();
    return kModuleOtherError;
  }
}

// The caller's side: throws again what a module's status stands for (nothing for kModuleOk).
template <class SimError>
void rethrow_module_status(int status, const std::string& error) {
  switch (status) {
    case kModuleOk: return;
    case kModuleSimError: throw SimError(error);
    case kModuleSceneError: throw scene::Error(error);
    default: throw std::runtime_error(error);
  }
}

}  // namespace rc::harness
