// The builtin Cornell box at fp24, loaded once per test binary: the small scene the harness and
// watchdog tests render (core_harness_test.cpp, core_watchdog_test.cpp).
#pragma once

#include "job.hpp"

namespace rc::test {

inline const RenderInput& cornell() {
  static const RenderInput in =
      load_render_input("builtin:cornell", scene::LoadOptions{}, scene::NumberFormat::fp24());
  return in;
}

}  // namespace rc::test
