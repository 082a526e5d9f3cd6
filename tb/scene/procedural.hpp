// Built-in procedural meshes, so the project works without any external file and so scale can be
// tested: a Cornell-style box with two blocks, a grid of tessellated spheres and gems, and a large
// generated terrain. Everything is deterministic (integer hashing, no random number library).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "mesh.hpp"

namespace rc::scene {

// NAME is cornell, spheres or terrain. params (a JSON object, may be empty) sets:
//   spheres: "count" (objects per side of the grid, default 5)
//   terrain: "grid" (cells per side, default 256: 131,072 triangles)
// Throws Error for an unknown name or parameter.
Mesh builtin_mesh(const std::string& name, const nlohmann::json& params);

}  // namespace rc::scene
