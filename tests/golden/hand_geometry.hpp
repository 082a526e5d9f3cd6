// Hand-built geometry for the golden model's rule tests (golden_rules_test.cpp,
// golden_light_test.cpp): triangles stored as the scene compiler stores them, squares, the root
// box and rays, all in fp24.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <glm/geometric.hpp>

#include "compiler.hpp"
#include "fp.hpp"
#include "trace.hpp"

namespace rc::test::hand {

using T = fp24;

inline T f(double x) { return T::from_double(x); }

inline void set_box(Geometry<T>& g, double lo, double hi) {
  for (int a = 0; a < 3; ++a) {
    g.bounds[a] = f(lo);
    g.bounds[a + 3] = f(hi);
  }
}

// Appends triangle (a, b, c) to g as the compiler would store it (transform, |n|, unit normal,
// material 0, which is white when g has no material yet); returns its index.
inline uint32_t add_tri(Geometry<T>& g, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  std::array<double, 12> m;
  EXPECT_TRUE(scene::unit_triangle_transform(a, b, c, &m));
  std::array<T, 12> mt;
  for (int k = 0; k < 12; ++k) mt[k] = f(m[k]);
  g.tris.push_back(mt);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  g.normal_len.push_back(f(glm::length(n)));
  const glm::dvec3 u = n / glm::length(n);
  g.normal.push_back({f(u.x), f(u.y), f(u.z)});
  g.material.push_back(0);
  if (g.kd.empty()) g.kd.push_back({f(1.0), f(1.0), f(1.0)});
  return static_cast<uint32_t>(g.tris.size() - 1);
}

// A square (two triangles) at depth z spanning [x0, x1] x [y0, y1], facing +z.
inline std::array<uint32_t, 2> add_quad(Geometry<T>& g, double x0, double x1, double y0, double y1,
                                        double z) {
  return {add_tri(g, {x0, y0, z}, {x1, y0, z}, {x0, y1, z}),
          add_tri(g, {x1, y0, z}, {x1, y1, z}, {x0, y1, z})};
}

// Appends a material (grey Kd kd, no specular term) with a mirror weight, a refraction weight and
// an index of refraction, first giving every per-material table of g the entries its triangles'
// default material 0 needs; returns its index.
inline uint32_t add_material(Geometry<T>& g, glm::dvec3 kd, double mirror = 0.0,
                             double transmit = 0.0, double ior = 1.0) {
  const auto fill = [&](size_t n) {
    g.kd.resize(n, {f(1.0), f(1.0), f(1.0)});
    g.ks.resize(n, {f(0.0), f(0.0), f(0.0)});
    g.ns.resize(n, 0);
    g.mirror.resize(n, f(0.0));
    g.transmit.resize(n, f(0.0));
    g.eta_enter.resize(n, f(1.0));
    g.eta_leave.resize(n, f(1.0));
  };
  const size_t i = g.kd.size();
  fill(i);
  fill(i + 1);
  g.kd[i] = {f(kd.x), f(kd.y), f(kd.z)};
  g.mirror[i] = f(mirror);
  g.transmit[i] = f(transmit);
  g.eta_leave[i] = f(ior);
  g.eta_enter[i] = f(1.0 / f(ior).to_double());
  return static_cast<uint32_t>(i);
}

inline Ray<T> ray(glm::dvec3 o, glm::dvec3 d) {
  Ray<T> r;
  for (int a = 0; a < 3; ++a) {
    r.org[a] = f(o[a]);
    r.dir[a] = f(d[a]);
  }
  r.inv_len = f(1.0 / glm::length(d));
  return r;
}

}  // namespace rc::test::hand
