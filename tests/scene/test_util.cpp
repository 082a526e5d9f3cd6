#include "test_util.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "error.hpp"
#include "models_dir.hpp"

#ifndef RC_SOURCE_DIR
#error "RC_SOURCE_DIR must be defined"
#endif
#ifndef RAYCORE_EXE
#error "RAYCORE_EXE must be defined"
#endif

namespace rc::test {

using rc::scene::KdNode;
using rc::scene::SceneImage;

void report_cases(const std::string& what, size_t cases, size_t mismatches) {
  std::cout << "[cases] " << what << ": " << cases << " cases, " << mismatches << " mismatches\n";
}

std::vector<Tri> scene_triangles(const rc::scene::Scene& scene) {
  std::vector<Tri> out;
  for (const auto& m : scene.meshes)
    for (const auto& t : m.triangles)
      out.push_back({m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]});
  return out;
}

bool tri_box_overlap(const std::array<double, 6>& box, const Tri& tri) {
  using L = long double;
  // The box axes, exactly.
  for (int a = 0; a < 3; ++a) {
    const double mn = std::min({tri[0][a], tri[1][a], tri[2][a]});
    const double mx = std::max({tri[0][a], tri[1][a], tri[2][a]});
    if (mn > box[a + 3] || mx < box[a]) return false;
  }
  L v[3][3];
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) v[k][a] = static_cast<L>(tri[k][a]);
  const auto separated = [&](const L axis[3]) {
    L bmin = 0, bmax = 0;
    for (int a = 0; a < 3; ++a) {
      const L p = axis[a] * static_cast<L>(box[a]), q = axis[a] * static_cast<L>(box[a + 3]);
      bmin += std::min(p, q);
      bmax += std::max(p, q);
    }
    L tmin = 0, tmax = 0;
    for (int k = 0; k < 3; ++k) {
      const L d = axis[0] * v[k][0] + axis[1] * v[k][1] + axis[2] * v[k][2];
      tmin = k == 0 ? d : std::min(tmin, d);
      tmax = k == 0 ? d : std::max(tmax, d);
    }
    return tmin > bmax || tmax < bmin;
  };
  L e[3][3];
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) e[k][a] = v[(k + 1) % 3][a] - v[k][a];
  const L n[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                  e[0][0] * e[1][1] - e[0][1] * e[1][0]};
  if (separated(n)) return false;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      L axis[3] = {0, 0, 0};  // unit_i x e_k
      const int a = (i + 1) % 3, b = (i + 2) % 3;
      axis[a] = -e[k][b];
      axis[b] = e[k][a];
      if (separated(axis)) return false;
    }
  }
  return true;
}

namespace {

double area(const std::array<double, 6>& b) {
  const double dx = b[3] - b[0], dy = b[4] - b[1], dz = b[5] - b[2];
  return 2.0 * (dx * dy + dy * dz + dz * dx);
}

}  // namespace

TreeCheck check_tree(const SceneImage& img, const std::vector<Tri>& tris) {
  TreeCheck r;
  const auto& f = img.format();
  const auto root_box = img.bounds();
  const double root_area = area(root_box);
  // Boxes of all nodes from the image alone; depth, SAH, sortedness, spurious entries.
  const size_t n = img.node_count();
  std::vector<std::array<double, 6>> boxes(n);
  struct Item {
    uint32_t node, depth;
  };
  std::vector<Item> stack{{0, 0}};
  boxes[0] = root_box;
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    ++r.nodes;
    r.depth = std::max(r.depth, it.depth);
    const KdNode node = img.node(it.node);
    const auto& box = boxes[it.node];
    if (node.is_leaf()) {
      ++r.leaves;
      r.sah += static_cast<double>(rc::spec::kKdtreeIntersectionCost) * node.count() * area(box) /
               root_area;
      uint32_t prev = 0;
      for (uint32_t k = 0; k < node.count(); ++k) {
        const uint32_t t = img.list_entry(node.first() + k);
        if (k > 0 && t <= prev) ++r.unsorted;
        prev = t;
        if (t < tris.size() && !tri_box_overlap(box, tris[t])) ++r.spurious;
      }
      continue;
    }
    r.sah += static_cast<double>(rc::spec::kKdtreeTraversalCost) * area(box) / root_area;
    const double s = f.decode(node.split_bits());
    boxes[node.left()] = box;
    boxes[node.left()][node.axis() + 3] = s;
    boxes[node.right()] = box;
    boxes[node.right()][node.axis()] = s;
    stack.push_back({node.right(), it.depth + 1});
    stack.push_back({node.left(), it.depth + 1});
  }
  // Every live triangle reaches every leaf it overlaps.
  std::vector<uint32_t> walk;
  for (size_t t = 0; t < tris.size(); ++t) {
    if (img.triangle_dropped(t)) continue;
    if (!tri_box_overlap(root_box, tris[t])) {
      ++r.missing;
      if (r.problems.size() < 10)
        r.problems.push_back("triangle " + std::to_string(t) + " is outside the root box");
      continue;
    }
    walk.assign(1, 0);
    while (!walk.empty()) {
      const uint32_t i = walk.back();
      walk.pop_back();
      const KdNode node = img.node(i);
      if (node.is_leaf()) {
        ++r.pairs;
        bool found = false;
        for (uint32_t k = 0; k < node.count() && !found; ++k)
          found = img.list_entry(node.first() + k) == t;
        if (!found) {
          ++r.missing;
          if (r.problems.size() < 10) {
            const auto& b = boxes[i];
            std::ostringstream ss;
            ss.precision(17);
            ss << "triangle " << t << " overlaps leaf " << i << " [" << b[0] << " " << b[1] << " "
               << b[2] << "]-[" << b[3] << " " << b[4] << " " << b[5] << "] but is not listed";
            r.problems.push_back(ss.str());
          }
        }
        continue;
      }
      if (tri_box_overlap(boxes[node.left()], tris[t])) walk.push_back(node.left());
      if (tri_box_overlap(boxes[node.right()], tris[t])) walk.push_back(node.right());
    }
  }
  return r;
}

void patch(std::vector<uint8_t>* img, size_t offset, uint64_t value, int bytes) {
  rc::scene::put_le(img, offset, value, bytes);
}

void fix_checksum(std::vector<uint8_t>* img) {
  patch(img, rc::spec::kImageHeaderChecksum, rc::scene::image_checksum(*img), 4);
}

const rc::scene::SectionInfo& section_of(const SceneImage& img, uint32_t id) {
  return img.section(id);
}

std::string temp_dir() {
  // Created on first use, removed with everything in it when the test process exits.
  struct Dir {
    std::string path;
    Dir() {
      char tmpl[] = "/tmp/rc_scene_test.XXXXXX";
      const char* d = mkdtemp(tmpl);
      if (!d) throw std::runtime_error("mkdtemp failed");
      path = d;
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = temp_dir() + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

std::vector<uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
}

void write_file(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

std::string models_dir() { return shared_models_dir(); }

std::vector<std::string> readme_models() {
  std::vector<std::string> out;
  const std::string dir = models_dir();
  if (dir.empty()) return out;
  std::ifstream in(dir + "/README.md");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != '|') continue;
    std::vector<std::string> cols;
    std::stringstream ss(line);
    std::string col;
    while (std::getline(ss, col, '|')) cols.push_back(col);
    if (cols.size() < 3) continue;
    std::string file = cols[2];
    file.erase(0, file.find_first_not_of(" \t`"));
    file.erase(file.find_last_not_of(" \t`") + 1);
    if (file.size() < 4 || file.compare(file.size() - 4, 4, ".obj") != 0) continue;
    const auto open = file.find('{'), close = file.find('}');
    if (open == std::string::npos || close == std::string::npos || close < open) {
      out.push_back(file);
      continue;
    }
    std::stringstream alts(file.substr(open + 1, close - open - 1));
    std::string alt;
    while (std::getline(alts, alt, ','))
      out.push_back(file.substr(0, open) + alt + file.substr(close + 1));
  }
  return out;
}

std::vector<std::string> repo_scenes() {
  std::vector<std::string> out;
  const std::string dir = std::string(RC_SOURCE_DIR) + "/scenes";
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

RunResult run_raycore(const std::vector<std::string>& args) {
  std::string cmd = "timeout 120 '" + std::string(RAYCORE_EXE) + "'";
  for (const auto& a : args) {
    std::string q;
    for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    cmd += " '" + q + "'";
  }
  cmd += " 2>&1";
  RunResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t got;
  while ((got = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, got);
  const int st = pclose(p);
  if (WIFEXITED(st)) r.status = WEXITSTATUS(st);
  return r;
}

}  // namespace rc::test
