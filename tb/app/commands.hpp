// raycore subcommands. Each group of subcommands lives in its own file (scene_command.cpp, ...)
// and registers itself on the top-level CLI::App through one function declared here; main.cpp
// calls every registration function.
//
// A subcommand's parse callback only stores the Action to run: main.cpp runs it after parsing, so
// usage errors (exit status 2) are told apart from errors while running (status 1, reported by
// throwing rc::scene::Error or another std::exception).
#pragma once

#include <functional>

namespace CLI {
class App;
}

namespace rc::app {

using Action = std::function<int()>;

// `raycore scene build` and `raycore scene info` (scene_command.cpp).
void add_scene_commands(CLI::App& app, Action* action);

// `raycore render` (render_command.cpp, built when the golden model library exists; see
// CMakeLists.txt).
void add_render_commands(CLI::App& app, Action* action);

}  // namespace rc::app
