#include "model_module.hpp"

#include <dlfcn.h>

#include <map>
#include <mutex>

#include "error.hpp"

#ifndef RC_MODULE_DIR
#error "RC_MODULE_DIR must name the directory of the model modules"
#endif

namespace rc::harness {

void* module_symbol(const std::string& name, const char* symbol) {
  static std::mutex mutex;
  static std::map<std::string, void*> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  void*& handle = loaded[name];
  const std::string path = std::string(RC_MODULE_DIR) + "/lib" + name + ".so";
  if (!handle) {
    handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = ::dlerror();
      throw scene::Error("the verilated model " + name + " is not built (" +
                         (why ? why : path.c_str()) + "): run `make` (or `cmake --build build " +
                         "--target " + name + "`) first; `make bench-models` for the cores only " +
                         "the benchmark uses");
    }
  }
  ::dlerror();
  void* fn = ::dlsym(handle, symbol);
  if (!fn) throw scene::Error(path + ": has no " + symbol + " (rebuild it: make)");
  return fn;
}

}  // namespace rc::harness
