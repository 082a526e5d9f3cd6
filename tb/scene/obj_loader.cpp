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
//
// The MTL files an OBJ names with `mtllib` get the same treatment: tinyobjloader reads them
// through our MaterialReader (CheckedMtlReader), which first checks every line that gives a number
// the image uses (check_mtl: Ka Kd Ks Ke Tf Kt Ns Ni d Tr illum; docs/memory-format.md, "MTL
// values") and then replaces tinyobjloader's numbers by the checked, correctly rounded ones.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

#include "error.hpp"
#include "mesh.hpp"
#include "number_format.hpp"

namespace rc::scene {

double Material::mirror() const {
  if (illum < 3 || illum > 7) return 0.0;
  return std::max(ks.r, std::max(ks.g, ks.b));
}

double Material::transmit() const {
  const bool refracts = illum == 4 || illum == 6 || illum == 7;
  const double tf_max = refracts ? std::max(tf.r, std::max(tf.g, tf.b)) : 0.0;
  return std::min(std::max(1.0 - dissolve, tf_max), 1.0);
}

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// Splits the rest of a line at blanks.
class Tokens {
 public:
  explicit Tokens(std::string_view s) : s_(s) {}
  std::string_view line() const { return s_; }
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

// The lines of a text, numbered from 1; "\n", "\r\n" and a lone "\r" end a line (as
// tinyobjloader's safeGetline counts them).
class Lines {
 public:
  explicit Lines(const std::string& text) : text_(text) {}
  bool next(std::string_view* line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find_first_of("\r\n", pos_);
    if (end == std::string::npos) end = text_.size();
    *line = std::string_view(text_.data() + pos_, end - pos_);
    pos_ = end;
    if (pos_ < text_.size() && text_[pos_] == '\r') {
      ++pos_;
      if (pos_ < text_.size() && text_[pos_] == '\n') ++pos_;
    } else if (pos_ < text_.size()) {
      ++pos_;  // '\n'
    }
    ++number_;
    return true;
  }
  uint32_t number() const { return number_; }

 private:
  const std::string& text_;
  size_t pos_ = 0;
  uint32_t number_ = 0;
};

Checked check_text(const std::string& text, const std::string& name) {
  Checked c;
  long max_index = 0;
  uint32_t max_index_line = 0;
  Lines lines(text);
  std::string_view full;
  while (lines.next(&full)) {
    const uint32_t line_no = lines.number();
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

// ---- MTL files

std::string num(double v) {
  std::ostringstream ss;
  ss << std::setprecision(9) << v;
  return ss.str();
}

// The largest value every image number format stores (fp24's largest finite value; fp32's is
// larger): an MTL number beyond it is refused whatever format the image is built in, so that an
// MTL file that builds at fp32 also builds at fp24.
const NumberFormat& mtl_format() {
  static const NumberFormat f = NumberFormat::fp24();
  return f;
}

// The numbers of one material as check_mtl() read them (unset: not given in the file).
struct MtlMaterial {
  std::optional<glm::dvec3> kd, ks, ke, tf;
  std::optional<double> ns, ior, dissolve;
  std::optional<int> illum;
  bool has_d = false;  // d wins over Tr, in whatever order they come (as in tinyobjloader)
};

struct MtlCheck {
  // One entry per material that tinyobjloader's LoadMtl adds, in its order: it flushes the
  // current material at each `newmtl` when it has a name and once more at the end of the file.
  std::vector<MtlMaterial> materials;
  std::vector<std::string> warnings;  // "FILE:LINE: ..."
};

enum class MtlRange { kColour, kNonNegative, kPositive, kUnit };

// One number of an MTL line: a decimal number (no trailing text), finite, storable in every image
// number format, and in the keyword's range. Throws Error("FILE:LINE: KEY: ...").
double mtl_number(std::string_view t, MtlRange range, const std::string& name, uint32_t line,
                  const std::string& key) {
  const std::string text(t);
  const std::string what = key + ": ";
  double v = 0.0;
  if (!parse_number(t, &v)) fail_line(name, line, what + "'" + text + "' is not a number");
  std::string lower;
  for (char ch : text) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (std::isnan(v) || (std::isinf(v) && lower.find("inf") != std::string::npos))
    fail_line(name, line, what + "'" + text + "' is not a finite number");
  const NumberFormat& f = mtl_format();
  if (!std::isfinite(f.round(v)))
    fail_line(name, line,
              what + text + " is too large: the largest " + f.name() + " value is " +
                  num(f.max_value()) + " (images store material values as fp24 or fp32)");
  switch (range) {
    case MtlRange::kColour:
      if (v < 0.0) fail_line(name, line, what + text + " is negative (colours are 0 or more)");
      break;
    case MtlRange::kNonNegative:
      if (v < 0.0) fail_line(name, line, what + text + " is negative (it must be 0 or more)");
      break;
    case MtlRange::kPositive:
      if (!(v > 0.0)) fail_line(name, line, what + text + " is not greater than 0");
      if (f.round(v) == 0.0)
        fail_line(name, line,
                  what + text + " is too small: the smallest " + f.name() + " value is " +
                      num(f.next_up(0.0)) + " (smaller ones flush to 0)");
      break;
    case MtlRange::kUnit:
      if (v < 0.0 || v > 1.0) fail_line(name, line, what + text + " is outside [0, 1]");
      break;
  }
  return v;
}

// The values after an MTL keyword, up to the end of the line or a '#' comment.
std::vector<std::string_view> mtl_values(Tokens* tok) {
  std::vector<std::string_view> out;
  std::string_view t;
  while (tok->next(&t) && t[0] != '#') out.push_back(t);
  return out;
}

// Ka Kd Ks Ke Tf Kt: three numbers r g b, or one number for grey (r = g = b, as the MTL
// specification says; tinyobjloader alone would read "Kd 0.5" as 0.5 0 0).
glm::dvec3 mtl_colour(Tokens* tok, const std::string& name, uint32_t line, const std::string& key) {
  const auto vals = mtl_values(tok);
  if (!vals.empty() && (vals[0] == "spectral" || vals[0] == "xyz"))
    fail_line(name, line,
              key + ": the '" + std::string(vals[0]) +
                  "' form is not supported (give r g b, or one number for grey)");
  if (vals.size() != 1 && vals.size() != 3)
    fail_line(name, line,
              key + ": expected 3 numbers r g b (or 1 number for grey), got " +
                  std::to_string(vals.size()) + " in " + quoted(tok->line()));
  if (vals.size() == 1) return glm::dvec3(mtl_number(vals[0], MtlRange::kColour, name, line, key));
  glm::dvec3 c;
  for (int k = 0; k < 3; ++k)
    c[k] = mtl_number(vals[static_cast<size_t>(k)], MtlRange::kColour, name, line, key);
  return c;
}

// Ns Ni d Tr illum: one value. More numbers after it are a warning (teapot/default.mtl of the
// shared models has "Tr 0  0"): tinyobjloader reads the first, and so do we.
std::string_view mtl_single(Tokens* tok, const std::string& name, uint32_t line,
                            const std::string& key, MtlCheck* c) {
  const auto vals = mtl_values(tok);
  if (vals.empty()) fail_line(name, line, key + ": expected a number, got nothing");
  for (size_t i = 1; i < vals.size(); ++i) {
    double ignored = 0.0;
    if (!parse_number(vals[i], &ignored))
      fail_line(name, line,
                key + ": expected one number, got " + quoted(tok->line()) + " ('" +
                    std::string(vals[i]) + "' is not a number)");
  }
  if (vals.size() > 1)
    c->warnings.push_back(name + ":" + std::to_string(line) + ": " + key + ": " +
                          std::to_string(vals.size()) +
                          " numbers where one is expected; the first is used");
  return vals[0];
}

MtlCheck check_mtl(const std::string& text, const std::string& name) {
  MtlCheck c;
  MtlMaterial cur;
  bool named = false;
  Lines lines(text);
  std::string_view full;
  while (lines.next(&full)) {
    const uint32_t line = lines.number();
    if (full.find('\0') != std::string_view::npos)
      fail_line(name, line, "NUL byte in the text (is this an MTL file?)");
    Tokens tok(full);
    std::string_view key_view;
    if (!tok.next(&key_view) || key_view[0] == '#') continue;
    const std::string key(key_view);
    if (key == "newmtl") {
      std::string_view material;
      if (!tok.next(&material)) fail_line(name, line, "newmtl without a material name");
      if (named) c.materials.push_back(cur);
      cur = MtlMaterial();
      named = true;
    } else if (key == "Ka") {
      (void)mtl_colour(&tok, name, line, key);  // checked, but the image has no ambient colour
    } else if (key == "Kd") {
      cur.kd = mtl_colour(&tok, name, line, key);
    } else if (key == "Ks") {
      cur.ks = mtl_colour(&tok, name, line, key);
    } else if (key == "Ke") {
      cur.ke = mtl_colour(&tok, name, line, key);
    } else if (key == "Tf" || key == "Kt") {
      cur.tf = mtl_colour(&tok, name, line, key);
    } else if (key == "Ns") {
      cur.ns = mtl_number(mtl_single(&tok, name, line, key, &c), MtlRange::kNonNegative, name, line,
                          key);
    } else if (key == "Ni") {
      cur.ior =
          mtl_number(mtl_single(&tok, name, line, key, &c), MtlRange::kPositive, name, line, key);
    } else if (key == "d") {
      cur.dissolve =
          mtl_number(mtl_single(&tok, name, line, key, &c), MtlRange::kUnit, name, line, key);
      cur.has_d = true;
    } else if (key == "Tr") {
      const double tr =
          mtl_number(mtl_single(&tok, name, line, key, &c), MtlRange::kUnit, name, line, key);
      if (!cur.has_d) cur.dissolve = 1.0 - tr;
    } else if (key == "illum") {
      const std::string_view t = mtl_single(&tok, name, line, key, &c);
      long illum = -1;
      if (!parse_index(t, &illum) || illum < 0 || illum > 10)
        fail_line(name, line,
                  "illum: '" + std::string(t) + "' is not an integer in 0..10 (the MTL models)");
      cur.illum = static_cast<int>(illum);
    }
  }
  c.materials.push_back(cur);
  return c;
}

// tinyobjloader's MaterialReader for the MTL files an OBJ names: the file is looked up in the
// OBJ's directory (an absolute name as given), checked with check_mtl(), parsed by tinyobjloader's
// LoadMtl, and the checked numbers replace LoadMtl's. A file that cannot be opened is what it was
// with tinyobjloader's own reader: a warning, and the faces that use its materials get the default
// material.
class CheckedMtlReader : public tinyobj::MaterialReader {
 public:
  explicit CheckedMtlReader(std::string dir) : dir_(std::move(dir)) {}

  bool operator()(const std::string& mat_id, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* mat_map, std::string* warn,
                  std::string* err) override {
    std::string path = mat_id;
    if (mat_id.empty() || mat_id[0] != '/')
      path = dir_.empty() ? mat_id : (dir_.back() == '/' ? dir_ : dir_ + "/") + mat_id;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      if (warn) *warn += "cannot open MTL file " + path + ": " + std::strerror(errno) + "\n";
      return false;
    }
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
      throw Error(path + ": cannot read MTL file: not a regular file");
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw Error(path + ": read error");
    const std::string text = ss.str();
    MtlCheck checked = check_mtl(text, path);

    const size_t base = materials->size();
    std::istringstream stream(text);
    std::string mtl_warn;
    tinyobj::LoadMtl(mat_map, materials, &stream, &mtl_warn, err);
    if (warn) *warn += mtl_warn;
    if (materials->size() - base != checked.materials.size())
      throw Error(path + ": internal error: tinyobjloader read " +
                  std::to_string(materials->size() - base) + " materials, the line check " +
                  std::to_string(checked.materials.size()));
    const auto rgb = [](tinyobj::real_t* out, const glm::dvec3& v) {
      for (int k = 0; k < 3; ++k) out[k] = static_cast<tinyobj::real_t>(v[k]);
    };
    for (size_t i = 0; i < checked.materials.size(); ++i) {
      const MtlMaterial& v = checked.materials[i];
      tinyobj::material_t& m = (*materials)[base + i];
      if (v.kd) rgb(m.diffuse, *v.kd);
      if (v.ks) rgb(m.specular, *v.ks);
      if (v.ke) rgb(m.emission, *v.ke);
      if (v.tf) rgb(m.transmittance, *v.tf);
      if (v.ns) m.shininess = static_cast<tinyobj::real_t>(*v.ns);
      if (v.ior) m.ior = static_cast<tinyobj::real_t>(*v.ior);
      if (v.dissolve) m.dissolve = static_cast<tinyobj::real_t>(*v.dissolve);
      if (v.illum) m.illum = *v.illum;
    }
    files_.push_back(path);
    warnings_.insert(warnings_.end(), checked.warnings.begin(), checked.warnings.end());
    return true;
  }

  const std::vector<std::string>& files() const { return files_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  std::string dir_;
  std::vector<std::string> files_;
  std::vector<std::string> warnings_;
};

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
  CheckedMtlReader mtl_reader(mtl_dir.empty() ? std::string(".") : mtl_dir);
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl_reader,
                                   /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!ok) throw Error(name + ": " + (err.empty() ? std::string("cannot parse OBJ") : err));
  if (!err.empty()) add_warnings(&mesh, err);  // MTL problems: the materials fall back
  add_warnings(&mesh, warn);
  mesh.warnings.insert(mesh.warnings.end(), mtl_reader.warnings().begin(),
                       mtl_reader.warnings().end());
  mesh.material_files = mtl_reader.files();

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
