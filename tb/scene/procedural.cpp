#include "procedural.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "error.hpp"
#include "scene.hpp"

namespace rc::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

class MeshBuilder {
 public:
  explicit MeshBuilder(const std::string& source) { mesh_.source = source; }

  uint32_t material(const Material& m) {
    mesh_.materials.push_back(m);
    return static_cast<uint32_t>(mesh_.materials.size() - 1);
  }
  uint32_t vertex(const glm::dvec3& p) {
    mesh_.vertices.push_back(p);
    return static_cast<uint32_t>(mesh_.vertices.size() - 1);
  }
  void tri(uint32_t a, uint32_t b, uint32_t c, uint32_t mat) {
    mesh_.triangles.push_back({a, b, c});
    mesh_.material.push_back(mat);
    mesh_.line.push_back(0);
  }
  // A quad a b c d (counter-clockwise seen from the side it faces) as the fan (a b c) (a c d).
  void quad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d,
            uint32_t mat) {
    const uint32_t ia = vertex(a), ib = vertex(b), ic = vertex(c), id = vertex(d);
    tri(ia, ib, ic, mat);
    tri(ia, ic, id, mat);
  }
  Mesh take() { return std::move(mesh_); }

 private:
  Mesh mesh_;
};

Material diffuse(const std::string& name, glm::dvec3 kd) {
  Material m;
  m.name = name;
  m.kd = kd;
  return m;
}

Material mirror(const std::string& name, glm::dvec3 kd, double reflect) {
  Material m = diffuse(name, kd);
  m.ks = glm::dvec3(reflect);
  m.ns = 200.0;
  m.illum = 3;
  return m;
}

Material glass(const std::string& name, glm::dvec3 tint) {
  Material m = diffuse(name, tint * 0.1);
  m.ks = glm::dvec3(0.1);
  m.tf = tint;
  m.ns = 300.0;
  m.dissolve = 0.1;
  m.ior = 1.5;
  m.illum = 7;
  return m;
}

glm::dvec3 rotate_y(const glm::dvec3& p, double deg) {
  const double a = deg * kPi / 180.0, c = std::cos(a), s = std::sin(a);
  return {c * p.x + s * p.z, p.y, -s * p.x + c * p.z};
}

// An axis-aligned block rotated about the vertical axis, standing on y = 0: four sides and a top.
void block(MeshBuilder* mb, glm::dvec3 center, glm::dvec3 size, double deg, uint32_t mat) {
  glm::dvec3 c[8];
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 corner((i & 1) ? 0.5 : -0.5, (i & 2) ? 1.0 : 0.0, (i & 4) ? 0.5 : -0.5);
    c[i] = center + rotate_y(corner * size, deg);
  }
  mb->quad(c[2], c[6], c[7], c[3], mat);  // top (+y)
  mb->quad(c[4], c[5], c[7], c[6], mat);  // +z
  mb->quad(c[1], c[0], c[2], c[3], mat);  // -z
  mb->quad(c[5], c[1], c[3], c[7], mat);  // +x
  mb->quad(c[0], c[4], c[6], c[2], mat);  // -x
}

// mirror_block: the tall block is a mirror (grey, reflect 0.8) instead of white.
Mesh cornell(bool mirror_block) {
  MeshBuilder mb("builtin:cornell");
  const uint32_t white = mb.material(diffuse("white", {0.73, 0.73, 0.73}));
  const uint32_t red = mb.material(diffuse("red", {0.65, 0.05, 0.05}));
  const uint32_t green = mb.material(diffuse("green", {0.12, 0.45, 0.15}));
  Material lamp = diffuse("light", {0.78, 0.78, 0.78});
  lamp.ke = {17.0, 12.0, 4.0};
  const uint32_t light = mb.material(lamp);
  const uint32_t tall = mirror_block ? mb.material(mirror("mirror", {0.1, 0.1, 0.1}, 0.8)) : white;
  // The box: x in [-1, 1], y in [0, 2], z in [-1, 1], open towards +z; walls face inwards.
  mb.quad({-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, white);    // floor
  mb.quad({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, white);    // ceiling
  mb.quad({-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}, white);  // back wall
  mb.quad({-1, 0, 1}, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, red);    // left wall
  mb.quad({1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}, green);      // right wall
  // The lamp, just below the ceiling, facing down.
  mb.quad({-0.25, 1.98, -0.25}, {0.25, 1.98, -0.25}, {0.25, 1.98, 0.25}, {-0.25, 1.98, 0.25},
          light);
  block(&mb, {0.34, 0.0, 0.32}, {0.6, 0.6, 0.6}, -18.0, white);  // short block
  block(&mb, {-0.34, 0.0, -0.3}, {0.6, 1.2, 0.6}, 17.0, tall);   // tall block
  return mb.take();
}

void uv_sphere(MeshBuilder* mb, glm::dvec3 c, double r, int seg_u, int seg_v, uint32_t mat) {
  std::vector<uint32_t> ring_prev, ring;
  const uint32_t top = mb->vertex(c + glm::dvec3(0, r, 0));
  const uint32_t bottom = mb->vertex(c - glm::dvec3(0, r, 0));
  for (int j = 1; j < seg_v; ++j) {
    const double phi = kPi * j / seg_v;
    ring.clear();
    for (int i = 0; i < seg_u; ++i) {
      const double theta = 2.0 * kPi * i / seg_u;
      ring.push_back(mb->vertex(c + r * glm::dvec3(std::sin(phi) * std::cos(theta), std::cos(phi),
                                                   -std::sin(phi) * std::sin(theta))));
    }
    for (int i = 0; i < seg_u; ++i) {
      const int k = (i + 1) % seg_u;
      if (j == 1) {
        mb->tri(top, ring[i], ring[k], mat);
      } else {
        mb->tri(ring_prev[i], ring[i], ring[k], mat);
        mb->tri(ring_prev[i], ring[k], ring_prev[k], mat);
      }
    }
    ring_prev.swap(ring);
  }
  for (int i = 0; i < seg_u; ++i) mb->tri(bottom, ring_prev[(i + 1) % seg_u], ring_prev[i], mat);
}

void icosphere(MeshBuilder* mb, glm::dvec3 c, double r, int levels, uint32_t mat) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                               {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                               {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p = glm::normalize(p);
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<int, 3>> next;
    for (const auto& tri : f) {
      int m[3];
      for (int e = 0; e < 3; ++e) {
        v.push_back(glm::normalize(v[tri[e]] + v[tri[(e + 1) % 3]]));
        m[e] = static_cast<int>(v.size() - 1);
      }
      next.push_back({tri[0], m[0], m[2]});
      next.push_back({tri[1], m[1], m[0]});
      next.push_back({tri[2], m[2], m[1]});
      next.push_back({m[0], m[1], m[2]});
    }
    f.swap(next);
  }
  std::vector<uint32_t> ids;
  for (const auto& p : v) ids.push_back(mb->vertex(c + r * p));
  for (const auto& tri : f) mb->tri(ids[tri[0]], ids[tri[1]], ids[tri[2]], mat);
}

// A brilliant-cut style gem with n facets around: a flat table, a crown, a girdle and a pavilion
// that ends in a point at the bottom.
void gem(MeshBuilder* mb, glm::dvec3 c, double r, int n, uint32_t mat) {
  const double table_r = 0.55 * r, table_y = 0.35 * r, girdle_y = 0.05 * r, apex_y = -0.75 * r;
  std::vector<uint32_t> table, girdle_top, girdle_bottom;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * kPi * i / n, b = a + kPi / n;
    table.push_back(
        mb->vertex(c + glm::dvec3(table_r * std::cos(b), table_y, -table_r * std::sin(b))));
    girdle_top.push_back(mb->vertex(c + glm::dvec3(r * std::cos(a), girdle_y, -r * std::sin(a))));
    girdle_bottom.push_back(
        mb->vertex(c + glm::dvec3(r * std::cos(a), -girdle_y, -r * std::sin(a))));
  }
  const uint32_t apex = mb->vertex(c + glm::dvec3(0, apex_y, 0));
  for (int i = 1; i + 1 < n; ++i) mb->tri(table[0], table[i], table[i + 1], mat);
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n;
    mb->tri(girdle_top[i], girdle_top[k], table[i], mat);             // crown, lower facets
    mb->tri(table[i], girdle_top[k], table[k], mat);                  // crown, star facets
    mb->tri(girdle_bottom[i], girdle_bottom[k], girdle_top[k], mat);  // girdle
    mb->tri(girdle_bottom[i], girdle_top[k], girdle_top[i], mat);
    mb->tri(apex, girdle_bottom[k], girdle_bottom[i], mat);  // pavilion
  }
}

Mesh spheres(int count) {
  MeshBuilder mb("builtin:spheres");
  const uint32_t ground = mb.material(diffuse("ground", {0.5, 0.5, 0.5}));
  const glm::dvec3 palette[] = {{0.8, 0.2, 0.2}, {0.2, 0.7, 0.3}, {0.2, 0.3, 0.8},
                                {0.9, 0.7, 0.2}, {0.7, 0.3, 0.8}, {0.2, 0.7, 0.8}};
  const double spacing = 1.2, r = 0.45;
  const double half = spacing * count / 2.0 + 0.5;
  mb.quad({-half, 0, half}, {half, 0, half}, {half, 0, -half}, {-half, 0, -half}, ground);
  for (int iz = 0; iz < count; ++iz) {
    for (int ix = 0; ix < count; ++ix) {
      const int q = iz * count + ix;
      const glm::dvec3 c(spacing * (ix - (count - 1) / 2.0), r, spacing * (iz - (count - 1) / 2.0));
      const glm::dvec3 colour = palette[q % 6];
      const std::string name = "object" + std::to_string(q);
      const uint32_t mat = q % 7 == 3   ? mb.material(glass(name, colour))
                           : q % 4 == 1 ? mb.material(mirror(name, colour, 0.8))
                                        : mb.material(diffuse(name, colour));
      switch (q % 3) {
        case 0: {
          const int seg = 12 + 6 * (q % 6);
          uv_sphere(&mb, c, r, seg, seg / 2, mat);
          break;
        }
        case 1: icosphere(&mb, c, r, (q / 3) % 4, mat); break;
        default: gem(&mb, c + glm::dvec3(0, 0.3 * r, 0), r, 6 + 2 * (q % 5), mat); break;
      }
    }
  }
  return mb.take();
}

// Value noise from an integer hash: deterministic on every machine.
double lattice(int64_t x, int64_t z, uint32_t seed) {
  uint32_t h = static_cast<uint32_t>(x) * 0x8da6b343u ^ static_cast<uint32_t>(z) * 0xd8163841u ^
               seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x85ebca6bu;
  h ^= h >> 16;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return static_cast<double>(h & 0xffffffu) / 16777216.0;
}

double value_noise(double x, double z, uint32_t seed) {
  const double fx = std::floor(x), fz = std::floor(z);
  const auto ix = static_cast<int64_t>(fx), iz = static_cast<int64_t>(fz);
  const double tx = x - fx, tz = z - fz;
  const double ux = tx * tx * (3.0 - 2.0 * tx), uz = tz * tz * (3.0 - 2.0 * tz);
  const double a = lattice(ix, iz, seed), b = lattice(ix + 1, iz, seed);
  const double c = lattice(ix, iz + 1, seed), d = lattice(ix + 1, iz + 1, seed);
  return (a + (b - a) * ux) + ((c + (d - c) * ux) - (a + (b - a) * ux)) * uz;
}

double terrain_height(double x, double z) {
  double sum = 0.0, amp = 1.0, freq = 1.0 / 24.0, norm = 0.0;
  for (uint32_t o = 0; o < 7; ++o) {
    sum += amp * value_noise(x * freq, z * freq, 17u + o);
    norm += amp;
    amp *= 0.5;
    freq *= 2.0;
  }
  const double h = 26.0 * (sum / norm - 0.42);
  return h < 0.0 ? 0.0 : h;  // a flat lake at sea level
}

Mesh terrain(int grid) {
  MeshBuilder mb("builtin:terrain");
  Material water = mirror("water", {0.05, 0.15, 0.3}, 0.3);
  const uint32_t m_water = mb.material(water);
  const uint32_t m_sand = mb.material(diffuse("sand", {0.76, 0.7, 0.5}));
  const uint32_t m_grass = mb.material(diffuse("grass", {0.25, 0.5, 0.15}));
  const uint32_t m_rock = mb.material(diffuse("rock", {0.45, 0.42, 0.4}));
  const uint32_t m_snow = mb.material(diffuse("snow", {0.95, 0.95, 0.97}));
  const double extent = 100.0;
  std::vector<uint32_t> ids;
  ids.reserve(static_cast<size_t>(grid + 1) * static_cast<size_t>(grid + 1));
  for (int j = 0; j <= grid; ++j) {
    for (int i = 0; i <= grid; ++i) {
      const double x = -extent / 2 + extent * i / grid, z = -extent / 2 + extent * j / grid;
      ids.push_back(mb.vertex({x, terrain_height(x, z), z}));
    }
  }
  const auto at = [&](int i, int j) { return ids[static_cast<size_t>(j) * (grid + 1) + i]; };
  const auto pick = [&](const std::array<uint32_t, 3>& t, const std::vector<glm::dvec3>& v) {
    const glm::dvec3 a = v[t[0]], b = v[t[1]], c = v[t[2]];
    const double y = (a.y + b.y + c.y) / 3.0;
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    if (a.y == 0.0 && b.y == 0.0 && c.y == 0.0) return m_water;
    if (y < 0.6) return m_sand;
    if (std::abs(n.y) < 0.75) return m_rock;
    if (y > 8.5) return m_snow;
    return m_grass;
  };
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      const std::array<uint32_t, 3> t1{at(i, j), at(i, j + 1), at(i + 1, j + 1)};
      const std::array<uint32_t, 3> t2{at(i, j), at(i + 1, j + 1), at(i + 1, j)};
      mb.tri(t1[0], t1[1], t1[2], 0);
      mb.tri(t2[0], t2[1], t2[2], 0);
    }
  }
  Mesh m = mb.take();
  for (size_t t = 0; t < m.triangles.size(); ++t) m.material[t] = pick(m.triangles[t], m.vertices);
  return m;
}

int int_param(const nlohmann::json& params, const std::string& scene, const std::string& key,
              int def, int lo, int hi) {
  if (!params.contains(key)) return def;
  const auto& v = params.at(key);
  if (!v.is_number_integer() || v.get<int64_t>() < lo || v.get<int64_t>() > hi)
    throw Error("builtin:" + scene + ": parameter '" + key + "' must be an integer in [" +
                std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v.get<int>();
}

void check_params(const nlohmann::json& params, const std::string& scene,
                  std::initializer_list<const char*> known) {
  if (params.is_null()) return;
  if (!params.is_object()) throw Error("builtin:" + scene + ": parameters must be a JSON object");
  for (const auto& item : params.items()) {
    if (std::none_of(known.begin(), known.end(), [&](const char* k) { return item.key() == k; }))
      throw Error("builtin:" + scene + ": unknown parameter '" + item.key() + "'");
  }
}

}  // namespace

Mesh builtin_mesh(const std::string& name, const nlohmann::json& params) {
  const nlohmann::json empty = nlohmann::json::object();
  const nlohmann::json& p = params.is_null() ? empty : params;
  if (name == "cornell") {
    check_params(p, name, {"mirror_block"});
    return cornell(int_param(p, name, "mirror_block", 0, 0, 1) != 0);
  }
  if (name == "spheres") {
    check_params(p, name, {"count"});
    return spheres(int_param(p, name, "count", 5, 1, 64));
  }
  if (name == "terrain") {
    check_params(p, name, {"grid"});
    return terrain(int_param(p, name, "grid", 256, 1, 2048));
  }
  std::string known;
  for (const auto& n : builtin_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown built-in scene 'builtin:" + name + "' (known: " + known + ")");
}

std::vector<std::string> builtin_names() { return {"cornell", "spheres", "terrain"}; }

Scene builtin_scene(const std::string& name) {
  Scene s;
  s.name = name;
  s.source = "builtin:" + name;
  s.meshes.push_back(builtin_mesh(name, nlohmann::json::object()));
  Camera cam;
  Light light;
  if (name == "cornell") {
    cam.eye = {0.0, 1.0, 3.8};
    cam.look = {0.0, 1.0, 0.0};
    cam.fov_deg = 39.3;
    light.position = {0.0, 1.9, 0.0};
  } else if (name == "spheres") {
    cam.eye = {0.0, 3.2, 7.0};
    cam.look = {0.0, 0.4, 0.0};
    cam.fov_deg = 40.0;
    light.position = {4.0, 8.0, 6.0};
  } else {
    cam.eye = {-55.0, 30.0, 55.0};
    cam.look = {5.0, 0.0, -5.0};
    cam.fov_deg = 45.0;
    light.type = Light::Type::kDirectional;
    light.position = {1.0, -1.0, -0.5};
    light.color = {1.0, 0.95, 0.85};
    s.background = {0.55, 0.7, 0.9};
  }
  s.camera = cam;
  s.lights.push_back(light);
  return s;
}

}  // namespace rc::scene
