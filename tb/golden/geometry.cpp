#include "geometry.hpp"

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
  for (size_t i = 0; i < n; ++i) {
    g.tris[i] = img.triangle<T>(i);
    const scene::ShadingRecord s = img.shading(i);
    g.material[i] = s.dropped() ? 0 : s.material;
    g.normal_len[i] = T::from_bits(s.normal_len_bits);
  }
  g.kd.resize(std::max<size_t>(img.material_count(), 1), {T::zero(), T::zero(), T::zero()});
  for (size_t i = 0; i < img.material_count(); ++i) {
    const scene::MaterialRecord m = img.material(i);
    for (int c = 0; c < 3; ++c) g.kd[i][c] = T::from_bits(m.kd[c]);
  }
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
      const glm::dvec3 kd = m.materials.empty() ? glm::dvec3(0.8) : m.materials[m.material[i]].kd;
      t.kd = {kd.x, kd.y, kd.z};
      out.push_back(t);
    }
  return out;
}

}  // namespace rc
