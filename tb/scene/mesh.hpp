// Triangle meshes as the scene compiler sees them: vertices in double, triangles in a fixed order,
// one material per triangle.
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace rc::scene {

// The shading parameters of an MTL material (the names are MTL's keywords).
struct Material {
  std::string name;
  glm::dvec3 kd{0.8, 0.8, 0.8};  // diffuse colour
  glm::dvec3 ks{0.0, 0.0, 0.0};  // specular colour (also the mirror reflectance, see mirror())
  glm::dvec3 ke{0.0, 0.0, 0.0};  // emission
  glm::dvec3 tf{0.0, 0.0, 0.0};  // transmission filter
  double ns = 0.0;               // specular exponent
  double dissolve = 1.0;         // d (opacity; MTL's Tr is 1 - d)
  double ior = 1.0;              // Ni
  int illum = 2;                 // MTL illumination model

  // Ray-traced reflection weight: MTL illumination models 3 to 7 turn ray-traced reflection on
  // with the specular colour as reflectance; this is its largest channel (0 for other models).
  double mirror() const;
  // Refraction weight: max(1 - d, t_f), at most 1, where t_f is Tf's largest channel for the MTL
  // models with refraction (illum 4, 6, 7) and 0 for the others.
  double transmit() const;
};

struct Mesh {
  std::string source;  // the file, or builtin:NAME; used in every message about this mesh
  std::vector<glm::dvec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;  // vertex indices, in OBJ order after the fan
  std::vector<uint32_t> material;                  // per triangle: index into materials
  std::vector<uint32_t> line;                      // per triangle: source line of its face, or 0
  std::vector<Material> materials;
  std::vector<std::string> material_files;  // the MTL files read for it (inputs too)
  std::vector<std::string> warnings;        // things worth telling the user that are not errors
};

// Loads an OBJ file (and the MTL files it names) through tinyobjloader. Polygons are fan
// triangulated here: a face v0..v(n-1) gives (v0, vi, vi+1) for i = 1..n-2, and triangle indices
// run over all faces in file order. Malformed lines, face indices out of range and meshes without
// faces throw rc::scene::Error naming the file and line. Vertex values are the correctly rounded
// doubles of the decimal text (NaN and infinities are kept: the compiler rejects the triangles that
// use them). The MTL files are checked line by line the same way (docs/memory-format.md, "MTL
// values"): a bad number, a value out of its range or one no image format can store throws Error
// naming the MTL file, the line and the keyword; an MTL file that cannot be opened is a warning
// and its materials fall back to the default.
Mesh load_obj(const std::string& path);

// Parses OBJ text (for tests); `name` is used in messages, MTL files are looked up in mtl_dir.
Mesh parse_obj(const std::string& text, const std::string& name, const std::string& mtl_dir);

}  // namespace rc::scene
