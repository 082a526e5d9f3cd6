// gen_seed_images: writes small, valid memory images for fuzz_image's seed corpus.
//
//   gen_seed_images OUT_DIR
//
// Compiles a handful of tiny scenes with the scene compiler (rc::scene::compile_scene) and writes
// OUT_DIR/gen-NAME.rcimg for each: one triangle (fp24 and fp32), two distant triangles with two
// materials and both light types (a tree with inner nodes), a scene with a degenerate (dropped)
// triangle, a tetrahedron seen from inside its bounds, and the built-in Cornell box. `make fuzz`
// runs it into the working corpus before every fuzz_image run, so the seeds always match the
// current image format; corpus/fuzz_image/ keeps a copy of its output for replaying by hand.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "compiler.hpp"
#include "error.hpp"
#include "image.hpp"
#include "scene.hpp"

namespace {

using rc::scene::Mesh;
using rc::scene::Scene;

Mesh mesh(const std::vector<glm::dvec3>& v, const std::vector<std::array<uint32_t, 3>>& t,
          const std::vector<uint32_t>& mat, const std::vector<rc::scene::Material>& mats) {
  Mesh m;
  m.source = "seed";
  m.vertices = v;
  m.triangles = t;
  m.material = mat;
  m.line.assign(t.size(), 0);
  m.materials = mats;
  return m;
}

rc::scene::Material material(const std::string& name, glm::dvec3 kd, int illum = 2) {
  rc::scene::Material m;
  m.name = name;
  m.kd = kd;
  m.illum = illum;
  if (illum >= 3) m.ks = glm::dvec3(0.5);
  return m;
}

Scene scene(const std::string& name, std::vector<Mesh> meshes, uint32_t w = 8, uint32_t h = 6) {
  Scene s;
  s.name = name;
  s.source = "seed:" + name;
  s.meshes = std::move(meshes);
  s.width = w;
  s.height = h;
  return s;
}

void write(const std::string& dir, const std::string& name, const Scene& s,
           rc::scene::NumberFormat format) {
  rc::scene::CompileOptions o;
  o.format = format;
  const rc::scene::Compiled c = rc::scene::compile_scene(s, o);
  const auto img = rc::scene::SceneImage::from_bytes(c.image, name);
  const auto problems = img.validate();
  if (!problems.empty()) throw rc::scene::Error(name + ": does not validate: " + problems.front());
  const std::string path = dir + "/gen-" + name + ".rcimg";
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(c.image.data()),
            static_cast<std::streamsize>(c.image.size()));
  if (!out) throw rc::scene::Error(path + ": cannot write");
  std::cout << path << ": " << c.image.size() << " bytes, " << img.node_count() << " nodes\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: gen_seed_images OUT_DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  const auto fp24 = rc::scene::NumberFormat::fp24();
  const auto fp32 = rc::scene::NumberFormat::fp32();
  try {
    const Mesh tri = mesh({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{0, 1, 2}}, {0},
                          {material("grey", {0.8, 0.8, 0.8})});
    write(dir, "triangle", scene("triangle", {tri}), fp24);
    write(dir, "triangle-fp32", scene("triangle", {tri}), fp32);

    Scene two = scene(
        "two", {mesh({{-3, -1, 0}, {-2, -1, 0}, {-2.5, 0, 0}, {2, 0, -1}, {3, 0, -1}, {2.5, 1, -1}},
                     {{0, 1, 2}, {3, 4, 5}}, {0, 1},
                     {material("red", {0.9, 0.1, 0.1}), material("mirror", {0.1, 0.1, 0.9}, 3)})});
    rc::scene::Light point, sun;
    point.position = {0, 2, 3};
    sun.type = rc::scene::Light::Type::kDirectional;
    sun.position = {0, -1, -1};
    two.lights = {point, sun};
    rc::scene::Camera cam;
    cam.eye = {0, 0, 6};
    cam.look = {0, 0, 0};
    two.camera = cam;
    two.background = {0.1, 0.2, 0.3};
    write(dir, "two-triangles", two, fp24);
    write(dir, "two-triangles-fp32", two, fp32);

    // A degenerate triangle (three collinear vertices) is dropped.
    write(dir, "dropped",
          scene("dropped", {mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 2}, {3, 3, 3}},
                                 {{0, 1, 2}, {0, 3, 4}}, {0, 0}, {material("white", {1, 1, 1})})}),
          fp24);

    Scene tet =
        scene("tetra", {mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                             {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}, {0, 1, 0, 1},
                             {material("a", {0.2, 0.9, 0.2}), material("b", {0.9, 0.9, 0.2}, 5)})});
    rc::scene::Camera inside;
    inside.eye = {0.2, 0.2, 0.2};
    inside.look = {1, 1, 1};
    inside.fov_deg = 90;
    tet.camera = inside;
    write(dir, "tetra", tet, fp24);

    write(dir, "cornell", rc::scene::builtin_scene("cornell"), fp24);
  } catch (const rc::scene::Error& e) {
    std::cerr << "gen_seed_images: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
