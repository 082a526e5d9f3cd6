// fuzz_obj: libFuzzer target for the OBJ/MTL loader, rc::scene::parse_obj (tb/scene/obj_loader.cpp,
// through tinyobjloader, whose implementation is compiled into this binary with the sanitizers).
//
// Input: OBJ text, optionally followed by a line starting with "#--mtl--" and MTL text. The MTL
// part is written to fuzz.mtl in this process's temporary directory, which is the directory
// parse_obj looks up mtllib files in (so "mtllib fuzz.mtl" loads it; without the separator no
// fuzz.mtl exists). See corpus/fuzz_obj/ for examples.
//
// Correct outcomes: a Mesh, or rc::scene::Error (but not "internal error: ..."). Findings:
// sanitizer reports, other exceptions, hangs, huge allocations, and a returned Mesh that breaks its
// invariants (a triangle naming a vertex or material out of range, per-triangle arrays of different
// lengths, no triangles).
// A small accepted mesh (at most kCompileMax triangles) is also compiled (compile_scene, fp24) and
// the image must pass SceneImage::from_bytes() and validate(): an OBJ the loader accepts must
// either compile into a well-formed image or be rejected with an Error.
//
// Build and run: `make fuzz` (tests/fuzz/fuzz.mk). By hand: build/fuzz/fuzz_obj CORPUS_DIR, or
// build/fuzz/fuzz_obj FILE to replay one input.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "compiler.hpp"
#include "error.hpp"
#include "fuzz_common.hpp"
#include "image.hpp"
#include "mesh.hpp"
#include "scene.hpp"

namespace {

constexpr size_t kCompileMax = 64;
const char kSeparator[] = "#--mtl--";

void check_mesh(const rc::scene::Mesh& m) {
  using rc::fuzz::fuzz_fail;
  const size_t nt = m.triangles.size();
  if (nt == 0) fuzz_fail("parse_obj returned a mesh without triangles");
  if (m.material.size() != nt || m.line.size() != nt)
    fuzz_fail("parse_obj: per-triangle arrays differ in length: " + std::to_string(nt) +
              " triangles, " + std::to_string(m.material.size()) + " materials, " +
              std::to_string(m.line.size()) + " lines");
  for (size_t t = 0; t < nt; ++t) {
    for (uint32_t v : m.triangles[t])
      if (v >= m.vertices.size())
        fuzz_fail("parse_obj: triangle " + std::to_string(t) + " names vertex " +
                  std::to_string(v) + " of " + std::to_string(m.vertices.size()));
    if (m.material[t] >= m.materials.size())
      fuzz_fail("parse_obj: triangle " + std::to_string(t) + " names material " +
                std::to_string(m.material[t]) + " of " + std::to_string(m.materials.size()));
  }
}

void compile_and_validate(const rc::scene::Mesh& mesh) {
  rc::scene::Scene scene;
  scene.name = "fuzz";
  scene.source = "fuzz.obj";
  scene.meshes.push_back(mesh);
  const rc::scene::Compiled c = rc::scene::compile_scene(scene, rc::scene::CompileOptions{});
  // From here on an Error is a finding: the compiler's own output must load and validate.
  try {
    const auto img = rc::scene::SceneImage::from_bytes(c.image, "compiled");
    const auto problems = img.validate();
    if (!problems.empty())
      rc::fuzz::fuzz_fail("the compiled image does not validate: " + problems.front());
  } catch (const rc::scene::Error& e) {
    rc::fuzz::fuzz_fail(std::string("the compiled image does not load: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::string obj = input, mtl;
  bool have_mtl = false;
  for (size_t pos = 0; pos < input.size();) {
    if (input.compare(pos, sizeof kSeparator - 1, kSeparator) == 0) {
      obj = input.substr(0, pos);
      const size_t eol = input.find('\n', pos);
      mtl = eol == std::string::npos ? std::string() : input.substr(eol + 1);
      have_mtl = true;
      break;
    }
    const size_t eol = input.find('\n', pos);
    if (eol == std::string::npos) break;
    pos = eol + 1;
  }

  const std::string& dir = rc::fuzz::temp_dir("obj");
  const std::string mtl_path = dir + "/fuzz.mtl";
  if (have_mtl) {
    std::ofstream out(mtl_path, std::ios::binary | std::ios::trunc);
    out << mtl;
    if (!out) rc::fuzz::fuzz_fail("cannot write " + mtl_path);
  } else {
    unlink(mtl_path.c_str());
  }

  try {
    const rc::scene::Mesh mesh = rc::scene::parse_obj(obj, "fuzz.obj", dir);
    check_mesh(mesh);
    if (mesh.triangles.size() <= kCompileMax) compile_and_validate(mesh);
  } catch (const rc::scene::Error& e) {
    // Rejected input: a correct outcome (unless the message admits an internal error).
    rc::fuzz::check_error_message(e.what());
  } catch (...) {
    rc::fuzz::fuzz_fail(rc::fuzz::describe_current_exception());
  }
  return 0;
}
