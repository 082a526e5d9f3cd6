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

#include <string>

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

}  // namespace rc::harness
