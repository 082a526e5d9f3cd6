#include "geometry.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <string>

#include "error.hpp"

namespace rc {

template <class T>
Geometry<T> load_geometry(const scene::SceneImage& img) {
  if (img.root_node() != 0)
    throw scene::Error(img.name() + ": root node is " + std::to_string(img.root_node()) +
                       ", the core starts at node 0");
  Geometry<T> g;
  const auto bb = img.bounds_bits();
  for (int i = 0; i < 6; ++i) g.bounds[i] = T::from_bits(bb[i]);
  g.nodes.resize(img.node_count());
  for (size_t i = 0; i < g.nodes.size(); ++i) g.nodes[i] = img.node(i).raw;
  g.lists.resize(img.list_size());
  for (size_t i = 0; i < g.lists.size(); ++i) g.lists[i] = img.list_entry(i);
  const size_t n = img.triangle_count();
  g.tris.resize(n);
  g.normal_len.resize(n);
  g.material.resize(n);
  g.normal.resize(n);
  for (size_t i = 0; i < n; ++i) {
    g.tris[i] = img.triangle<T>(i);
    const scene::ShadingRecord s = img.shading(i);
    g.material[i] = s.dropped() ? 0 : s.material;
    g.normal_len[i] = T::from_bits(s.normal_len_bits);
    for (int a = 0; a < 3; ++a) g.normal[i][a] = T::from_bits(s.normal_bits[a]);
  }
  const size_t materials = std::max<size_t>(img.material_count(), 1);
  g.kd.resize(materials, {T::zero(), T::zero(), T::zero()});
  g.ks.resize(materials, {T::zero(), T::zero(), T::zero()});
  g.ns.resize(materials, 0);
  g.mirror.resize(materials, T::zero());
  g.transmit.resize(materials, T::zero());
  g.eta_enter.resize(materials, T::one());
  g.eta_leave.resize(materials, T::one());
  for (size_t i = 0; i < img.material_count(); ++i) {
    const scene::MaterialRecord m = img.material(i);
    for (int c = 0; c < 3; ++c) {
      g.kd[i][c] = T::from_bits(m.kd[c]);
      g.ks[i][c] = T::from_bits(m.ks[c]);
    }
    g.ns[i] = light_exponent(T::from_bits(m.ns));
    g.mirror[i] = T::from_bits(m.mirror);
    g.transmit[i] = T::from_bits(m.transmit);
    // The ratios of refraction (docs/architecture.md, "Refraction"): entering, 1 / ior in double
    // rounded once; leaving, ior.
    g.eta_leave[i] = T::from_bits(m.ior);
    g.eta_enter[i] = T::from_double(1.0 / g.eta_leave[i].to_double());
  }
  // Lighting (docs/architecture.md, "Lighting"): each value computed in double from the image's
  // float32 fields and rounded to the format once.
  for (size_t i = 0; i < img.light_count(); ++i) {
    const scene::LightRecord r = img.light(i);
    typename Geometry<T>::Light l;
    l.directional = r.type == spec::kImageLightTypeDirectional;
    const glm::dvec3 v(r.position[0], r.position[1], r.position[2]);
    const glm::dvec3 toward = l.directional ? -v / glm::length(v) : v;
    for (int a = 0; a < 3; ++a) {
      l.pos[a] = T::from_double(toward[a]);
      l.color[a] = T::from_double(static_cast<double>(r.color[a]) * r.intensity);
    }
    g.lights.push_back(l);
  }
  double diag2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double e = g.bounds[a + 3].to_double() - g.bounds[a].to_double();
    diag2 += e * e;
  }
  g.t_eps = T::from_double(std::sqrt(diag2) * kShadowEpsScale);
  for (size_t i = 0; i < n; ++i)
    if (g.material[i] >= g.kd.size())
      throw scene::Error(img.name() + ": triangle " + std::to_string(i) + " names material " +
                         std::to_string(g.material[i]) + ", the image has " +
                         std::to_string(img.material_count()));
  return g;
}

template Geometry<fp24> load_geometry<fp24>(const scene::SceneImage&);
template Geometry<fp32ftz> load_geometry<fp32ftz>(const scene::SceneImage&);

std::vector<SoupTriangle> triangle_soup(const scene::Scene& s) {
  std::vector<SoupTriangle> out;
  for (const auto& m : s.meshes)
    for (size_t i = 0; i < m.triangles.size(); ++i) {
      SoupTriangle t;
      for (int k = 0; k < 3; ++k) t.v[k] = m.vertices[m.triangles[i][k]];
      const scene::Material mat =
          m.materials.empty() ? scene::Material{} : m.materials[m.material[i]];
      t.kd = {mat.kd.x, mat.kd.y, mat.kd.z};
      t.ks = {mat.ks.x, mat.ks.y, mat.ks.z};
      t.ns = mat.ns;
      t.mirror = mat.mirror();
      t.transmit = mat.transmit();
      t.ior = mat.ior;
      out.push_back(t);
    }
  return out;
}

}  // namespace rc

namespace rc {

std::vector<SoupLight> soup_lights(const scene::Scene& s) {
  std::vector<SoupLight> out;
  for (const auto& l : s.lights) {
    SoupLight sl;
    sl.directional = l.type == scene::Light::Type::kDirectional;
    sl.pos = sl.directional ? -l.position / glm::length(l.position) : l.position;
    sl.color = l.color * l.intensity;
    out.push_back(sl);
  }
  return out;
}

}  // namespace rc
