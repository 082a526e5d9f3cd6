// raycore: the project's command line. Subcommands are registered from their own files
// (commands.hpp).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <new>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"raycore: scene compiler and tools of the raycore ray tracing core"};
  app.require_subcommand(1);
  rc::app::Action action;
  rc::app::add_scene_commands(app, &action);
  rc::app::add_render_commands(app, &action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help (status 0) or the usage error
    return code == 0 ? 0 : 2;
  }
  if (!action) {
    std::cerr << app.help();
    return 2;
  }
  try {
    return action();
  } catch (const std::bad_alloc&) {
    std::cerr << "raycore: error: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << "raycore: error: " << e.what() << "\n";
  }
  return 1;
}
