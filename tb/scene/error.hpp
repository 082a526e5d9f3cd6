// raycore scene compiler: the one exception type of the library.
//
// Every problem the scene compiler or the image reader finds is reported by throwing
// rc::scene::Error with a message that names the file (or built-in scene) and the problem. The
// command line prints the message and exits with status 1.
#pragma once

#include <stdexcept>
#include <string>

namespace rc::scene {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rc::scene
