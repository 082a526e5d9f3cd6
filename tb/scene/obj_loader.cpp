// OBJ/MTL loading: a strict line check of our own, then tinyobjloader for the faces, groups and
// materials.
//
// tinyobjloader is lenient (a coordinate it cannot parse reads as 0, "nan" included, and index
// errors only produce warnings), so the text is first checked line by line here: vertex lines must
// hold 3 to 7 numbers, face lines at least 3 well-formed vertex references with indices in range.
// The same pass keeps the correctly rounded value of every coordinate (std::from_chars), which the
// loader uses instead of tinyobjloader's approximate decimal conversion. tinyobjloader then parses
// the same text without triangulating (its own triangulation is not a fan), and the faces are fan
// triangulated here in file order.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>

#include "error.hpp"
#include "mesh.hpp"

namespace rc::scene {

double Material::mirror() const {
  if (illum < 3 || illum > 7) return 0.0;
  return std::max(ks.r, std::max(ks.g, ks.b));
}

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// Splits the rest of a line at blanks.
class Tokens {
 public:
  explicit Tokens(std::string_view s) : s_(s) {}
  bool next(std::string_view* out) {
    while (pos_ < s_.size() && is_blank(s_[pos_])) ++pos_;
    if (pos_ >= s_.size()) return false;
    const size_t start = pos_;
    while (pos_ < s_.size() && !is_blank(s_[pos_])) ++pos_;
    *out = s_.substr(start, pos_ - start);
    return true;
  }

 private:
  std::string_view s_;
  size_t pos_ = 0;
};

// A decimal number, correctly rounded; "nan", "inf" and out-of-range values are accepted (as NaN,
// infinity, or the rounded value) so that the compiler can name the triangle that uses them.
bool parse_number(std::string_view t, double* out) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const char* end = t.data() + t.size();
  const auto res = std::from_chars(t.data(), end, *out, std::chars_format::general);
  if (res.ptr != end) return false;
  if (res.ec == std::errc::result_out_of_range) {
    const std::string copy(t);
    *out = std::strtod(copy.c_str(), nullptr);  // +-HUGE_VAL (inf) or the underflowed value
    return true;
  }
  return res.ec == std::errc();
}

bool parse_index(std::string_view t, long* out) {
  if (t.empty()) return false;
  const char* end = t.data() + t.size();
  const auto res = std::from_chars(t.data(), end, *out);
  return res.ec == std::errc() && res.ptr == end;
}

struct Checked {
  std::vector<glm::dvec3> vertices;
  std::vector<uint32_t> face_lines;  // one per face
};

[[noreturn]] void fail_line(const std::string& name, uint32_t line, const std::string& what) {
  throw Error(name + ":" + std::to_string(line) + ": " + what);
}

std::string quoted(std::string_view line) {
  std::string s(line.substr(0, 80));
  if (line.size() > 80) s += "...";
  return "'" + s + "'";
}

Checked check_text(const std::string& text, const std::string& name) {
  Checked c;
  uint32_t line_no = 0;
  size_t pos = 0;
  long max_index = 0;
  uint32_t max_index_line = 0;
  while (pos < text.size()) {
    size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    const std::string_view full(text.data() + pos, end - pos);
    pos = end;
    if (pos < text.size() && text[pos] == '\r') {
      ++pos;
      if (pos < text.size() && text[pos] == '\n') ++pos;
    } else if (pos < text.size()) {
      ++pos;  // '\n'
    }
    ++line_no;
    if (full.find('\0') != std::string_view::npos)
      fail_line(name, line_no, "NUL byte in the text (is this an OBJ file?)");
    Tokens tok(full);
    std::string_view key;
    if (!tok.next(&key) || key[0] == '#') continue;
    if (key == "v") {
      double xyz[7];
      int n = 0;
      std::string_view t;
      while (tok.next(&t)) {
        if (t[0] == '#') break;
        if (n == 7 || !parse_number(t, &xyz[n]))
          fail_line(name, line_no,
                    "malformed vertex line " + quoted(full) + " (expected 3 to 7 numbers)");
        ++n;
      }
      if (n < 3)
        fail_line(name, line_no, "malformed vertex line " + quoted(full) + " (expected x y z)");
      c.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
    } else if (key == "f") {
      int n = 0;
      std::string_view t;
      while (tok.next(&t)) {
        // v, v/vt, v//vn or v/vt/vn; every index given must be a non-zero integer.
        const size_t s1 = t.find('/');
        const std::string_view vs = t.substr(0, s1);
        long v = 0;
        bool ok = parse_index(vs, &v) && v != 0;
        if (ok && s1 != std::string_view::npos) {
          const std::string_view rest = t.substr(s1 + 1);
          const size_t s2 = rest.find('/');
          const std::string_view vt = rest.substr(0, s2);
          long idx = 0;
          if (!vt.empty()) ok = parse_index(vt, &idx) && idx != 0;
          if (ok && s2 != std::string_view::npos)
            ok = parse_index(rest.substr(s2 + 1), &idx) && idx != 0;
          else if (ok && vt.empty())
            ok = false;  // "v/" is not a reference
        }
        if (!ok)
          fail_line(name, line_no,
                    "malformed face line " + quoted(full) + ": bad vertex reference '" +
                        std::string(t) + "'");
        const long count = static_cast<long>(c.vertices.size());
        if (v < 0 && -v > count)
          fail_line(name, line_no,
                    "face vertex index " + std::to_string(v) + " is out of range (only " +
                        std::to_string(count) + " vertices before this line)");
        if (v > max_index) {
          max_index = v;
          max_index_line = line_no;
        }
        ++n;
      }
      if (n < 3)
        fail_line(name, line_no,
                  "malformed face line " + quoted(full) + ": a face needs at least 3 vertices");
      if (n > 255)
        fail_line(name, line_no,
                  "face with " + std::to_string(n) + " vertices (at most 255 are supported)");
      c.face_lines.push_back(line_no);
    }
  }
  if (max_index > static_cast<long>(c.vertices.size()))
    fail_line(name, max_index_line,
              "face vertex index " + std::to_string(max_index) + " is out of range (the file has " +
                  std::to_string(c.vertices.size()) + " vertices)");
  return c;
}

Material convert(const tinyobj::material_t& m) {
  Material out;
  out.name = m.name;
  out.kd = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
  out.ks = {m.specular[0], m.specular[1], m.specular[2]};
  out.ke = {m.emission[0], m.emission[1], m.emission[2]};
  out.tf = {m.transmittance[0], m.transmittance[1], m.transmittance[2]};
  out.ns = m.shininess;
  out.dissolve = m.dissolve;
  out.ior = m.ior;
  out.illum = m.illum;
  return out;
}

// tinyobjloader's warnings, one per line; the frequent "both d and Tr" note is summarised.
void add_warnings(Mesh* mesh, const std::string& text) {
  std::istringstream in(text);
  std::string line;
  size_t both_d_tr = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line == ".") continue;
    if (line.find("Both `d` and `Tr`") != std::string::npos) {
      ++both_d_tr;
      continue;
    }
    mesh->warnings.push_back(mesh->source + ": " + line);
  }
  if (both_d_tr > 0)
    mesh->warnings.push_back(mesh->source + ": " + std::to_string(both_d_tr) +
                             " materials give both d and Tr; d is used for the dissolve");
}

}  // namespace

Mesh parse_obj(const std::string& text, const std::string& name, const std::string& mtl_dir) {
  Checked checked = check_text(text, name);
  Mesh mesh;
  mesh.source = name;

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::istringstream in(text);
  tinyobj::MaterialFileReader mtl_reader(mtl_dir.empty() ? std::string(".") : mtl_dir);
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl_reader,
                                   /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!ok) throw Error(name + ": " + (err.empty() ? std::string("cannot parse OBJ") : err));
  if (!err.empty()) add_warnings(&mesh, err);  // MTL problems: the materials fall back
  add_warnings(&mesh, warn);

  const size_t nv = checked.vertices.size();
  if (attrib.vertices.size() != 3 * nv)
    throw Error(name + ": internal error: tinyobjloader read " +
                std::to_string(attrib.vertices.size() / 3) + " vertices, the line check " +
                std::to_string(nv));
  mesh.vertices = std::move(checked.vertices);

  size_t face = 0;
  bool needs_default = false;
  for (const auto& shape : shapes) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
      const size_t n = shape.mesh.num_face_vertices[f];
      if (face >= checked.face_lines.size())
        throw Error(name + ": internal error: tinyobjloader found more faces than the line check");
      const uint32_t line = checked.face_lines[face];
      const int mat = shape.mesh.material_ids[f];
      if (mat < 0) needs_default = true;
      const uint32_t mat_index =
          mat < 0 ? static_cast<uint32_t>(materials.size()) : static_cast<uint32_t>(mat);
      uint32_t idx[256];
      for (size_t k = 0; k < n; ++k) {
        const int v = shape.mesh.indices[offset + k].vertex_index;
        if (v < 0 || static_cast<size_t>(v) >= nv)
          fail_line(name, line,
                    "face vertex index " + std::to_string(v + 1) + " is out of range (" +
                        std::to_string(nv) + " vertices)");
        idx[k] = static_cast<uint32_t>(v);
      }
      for (size_t k = 1; k + 1 < n; ++k) {
        mesh.triangles.push_back({idx[0], idx[k], idx[k + 1]});
        mesh.material.push_back(mat_index);
        mesh.line.push_back(line);
      }
      offset += n;
    }
  }
  if (face != checked.face_lines.size())
    throw Error(name + ": internal error: tinyobjloader found " + std::to_string(face) +
                " faces, the line check " + std::to_string(checked.face_lines.size()));
  if (mesh.triangles.empty()) throw Error(name + ": the mesh is empty (no faces)");

  for (const auto& m : materials) mesh.materials.push_back(convert(m));
  if (needs_default) {
    Material def;
    def.name = "(default)";
    mesh.materials.push_back(def);
  }
  return mesh;
}

Mesh load_obj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open OBJ file: " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error(path + ": read error");
  const auto slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash);
  return parse_obj(ss.str(), path, dir.empty() ? "/" : dir);
}

}  // namespace rc::scene
