#include "compiler.hpp"

#include <chrono>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "error.hpp"
#include "image.hpp"

namespace rc::scene {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string num(double v) {
  std::ostringstream ss;
  ss << std::setprecision(9) << v;
  return ss.str();
}

// float32 of a format value (exact for every format with E <= 8 and F <= 23).
float to_f32(double v) { return static_cast<float>(v); }

void put_value(std::vector<uint8_t>* buf, size_t offset, uint32_t bits, int bytes) {
  put_le(buf, offset, bits, bytes);
}

}  // namespace

bool unit_triangle_transform(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                             std::array<double, 12>* m) {
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 n = glm::cross(e1, e2);
  const double n2 = glm::dot(n, n);
  if (!(n2 > 0.0) || !std::isfinite(n2)) return false;
  // The inverse of the matrix with columns e1, e2, n: its determinant is n . n.
  const glm::dvec3 rows[3] = {glm::cross(e2, n) / n2, glm::cross(n, e1) / n2, n / n2};
  for (int r = 0; r < 3; ++r) {
    (*m)[4 * r + 0] = rows[r].x;
    (*m)[4 * r + 1] = rows[r].y;
    (*m)[4 * r + 2] = rows[r].z;
    (*m)[4 * r + 3] = -glm::dot(rows[r], a);
  }
  return true;
}

Compiled compile_scene(const Scene& scene, const CompileOptions& options) {
  const NumberFormat& fmt = options.format;
  const int vb = fmt.value_bytes();
  Compiled out;
  BuildStats& st = out.stats;
  st.input = scene.source;
  st.scene_name = scene.name;
  st.format = fmt.name();
  st.meshes = scene.meshes.size();
  st.lights = scene.lights.size();
  st.depth_limit = options.kd.max_depth;
  for (const auto& m : scene.meshes) {
    st.triangles += m.triangles.size();
    st.vertices += m.vertices.size();
    st.materials += m.materials.size();
    st.warnings.insert(st.warnings.end(), m.warnings.begin(), m.warnings.end());
  }
  if (st.triangles == 0) throw Error(scene.source + ": the scene has no triangles");
  if (st.triangles > UINT32_MAX) throw Error(scene.source + ": too many triangles");
  if (st.materials >= ShadingRecord::kDropped) throw Error(scene.source + ": too many materials");

  // Checks, transforms and shading records, in triangle order.
  auto t0 = Clock::now();
  const size_t nt = st.triangles;
  const int64_t tri_stride = spec::kImageTriangleValues * vb;
  std::vector<uint8_t> tri_bytes(nt * static_cast<size_t>(tri_stride), 0);
  const uint32_t shade_stride = shading_stride(vb);
  std::vector<uint8_t> shade_bytes(nt * shade_stride, 0);
  std::vector<std::array<glm::dvec3, 3>> live;
  std::vector<uint32_t> live_ids;
  live.reserve(nt);
  live_ids.reserve(nt);
  glm::dvec3 lo(std::numeric_limits<double>::infinity()),
      hi(-std::numeric_limits<double>::infinity());
  size_t g = 0, material_base = 0;
  for (const auto& mesh : scene.meshes) {
    for (size_t t = 0; t < mesh.triangles.size(); ++t, ++g) {
      const auto& idx = mesh.triangles[t];
      const std::array<glm::dvec3, 3> v = {mesh.vertices[idx[0]], mesh.vertices[idx[1]],
                                           mesh.vertices[idx[2]]};
      for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 3; ++a) {
          const double x = v[k][a];
          if (std::abs(x) <= fmt.max_value()) continue;  // false for NaN too
          std::string where = mesh.source + ": triangle " + std::to_string(t);
          if (mesh.line[t] != 0) where += " (face on line " + std::to_string(mesh.line[t]) + ")";
          if (scene.meshes.size() > 1) where += " (scene triangle " + std::to_string(g) + ")";
          const std::string what =
              std::isfinite(x)
                  ? " is outside the " + fmt.name() + " range (|x| <= " + num(fmt.max_value()) + ")"
                  : " is not a finite number";
          throw Error(where + ": vertex " + std::to_string(idx[k] + 1) + " coordinate " + "xyz"[a] +
                      " = " + num(x) + what);
        }
      }
      std::array<double, 12> m{};
      bool ok = unit_triangle_transform(v[0], v[1], v[2], &m);
      std::array<uint32_t, 12> bits{};
      if (ok) {
        for (int k = 0; k < 12; ++k) {
          bits[k] = fmt.encode(m[k]);
          ok = ok && fmt.finite_bits(bits[k]);
        }
        // Flush-to-zero must not wipe out a row of the linear part.
        for (int r = 0; r < 3 && ok; ++r)
          ok = bits[4 * r] != 0 || bits[4 * r + 1] != 0 || bits[4 * r + 2] != 0;
      }
      const size_t srec = g * shade_stride;
      if (!ok) {
        ++st.dropped;
        put_le(&shade_bytes, srec + spec::kImageShadingMaterial, ShadingRecord::kDropped, 4);
        continue;
      }
      for (int k = 0; k < 12; ++k)
        put_value(&tri_bytes, g * static_cast<size_t>(tri_stride) + static_cast<size_t>(k * vb),
                  bits[k], vb);
      const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
      const double len = std::sqrt(glm::dot(n, n));
      put_le(&shade_bytes, srec + spec::kImageShadingMaterial, material_base + mesh.material[t], 4);
      for (int a = 0; a < 3; ++a)
        put_value(&shade_bytes,
                  srec + shading_value_offset(static_cast<int>(spec::kImageShadingNormal) + a, vb),
                  fmt.encode(n[a] / len), vb);
      put_value(&shade_bytes,
                srec + shading_value_offset(static_cast<int>(spec::kImageShadingNormalLen), vb),
                fmt.encode(len), vb);
      for (int k = 0; k < 3; ++k) {
        lo = glm::min(lo, v[k]);
        hi = glm::max(hi, v[k]);
      }
      live.push_back(v);
      live_ids.push_back(static_cast<uint32_t>(g));
    }
    material_base += mesh.materials.size();
  }
  if (live.empty())
    throw Error(scene.source + ": all " + std::to_string(nt) +
                " triangles are degenerate (zero area, or their transform does not fit " +
                fmt.name() + ")");
  Box root;
  for (int a = 0; a < 3; ++a) {
    root.lo[a] = fmt.round_down(lo[a]);
    root.hi[a] = fmt.round_up(hi[a]);
  }
  st.transform_ms = ms_since(t0);

  t0 = Clock::now();
  const KdTree tree = build_kdtree(live, live_ids, root, fmt, options.kd);
  st.build_ms = ms_since(t0);

  t0 = Clock::now();
  ImageWriter w(fmt);
  for (int a = 0; a < 3; ++a) {
    st.bounds[a] = root.lo[a];
    st.bounds[a + 3] = root.hi[a];
    w.bounds_value[a] = fmt.encode(root.lo[a]);
    w.bounds_value[a + 3] = fmt.encode(root.hi[a]);
    w.bounds_f32[a] = to_f32(root.lo[a]);
    w.bounds_f32[a + 3] = to_f32(root.hi[a]);
  }
  w.tree_depth = tree.depth;
  w.triangle_count = static_cast<uint32_t>(nt);
  w.dropped_count = static_cast<uint32_t>(st.dropped);

  std::vector<uint8_t> node_bytes(tree.nodes.size() * spec::kKdNodeBytes);
  for (size_t i = 0; i < tree.nodes.size(); ++i)
    put_le(&node_bytes, i * spec::kKdNodeBytes, tree.nodes[i].raw, spec::kKdNodeBytes);
  std::vector<uint8_t> list_bytes(tree.lists.size() * spec::kKdListEntryBytes);
  for (size_t i = 0; i < tree.lists.size(); ++i)
    put_le(&list_bytes, i * spec::kKdListEntryBytes, tree.lists[i], spec::kKdListEntryBytes);

  std::vector<uint8_t> strings;
  std::vector<uint8_t> mat_bytes(st.materials * spec::kImageMaterialStride, 0);
  size_t mi = 0;
  for (const auto& mesh : scene.meshes) {
    for (const auto& m : mesh.materials) {
      const size_t r = mi++ * spec::kImageMaterialStride;
      put_le(&mat_bytes, r + spec::kImageMaterialIllum, static_cast<uint32_t>(std::max(m.illum, 0)),
             4);
      put_le(&mat_bytes, r + spec::kImageMaterialName, strings.size(), 4);
      strings.insert(strings.end(), m.name.begin(), m.name.end());
      strings.push_back(0);
      for (int k = 0; k < 3; ++k) {
        put_le(&mat_bytes, r + spec::kImageMaterialKd + 4 * k, fmt.encode(m.kd[k]), 4);
        put_le(&mat_bytes, r + spec::kImageMaterialKs + 4 * k, fmt.encode(m.ks[k]), 4);
        put_le(&mat_bytes, r + spec::kImageMaterialKe + 4 * k, fmt.encode(m.ke[k]), 4);
        put_le(&mat_bytes, r + spec::kImageMaterialTf + 4 * k, fmt.encode(m.tf[k]), 4);
      }
      put_le(&mat_bytes, r + spec::kImageMaterialNs, fmt.encode(m.ns), 4);
      put_le(&mat_bytes, r + spec::kImageMaterialMirror, fmt.encode(m.mirror()), 4);
      put_le(&mat_bytes, r + spec::kImageMaterialTransmit, fmt.encode(m.transmit()), 4);
      put_le(&mat_bytes, r + spec::kImageMaterialDissolve, fmt.encode(m.dissolve), 4);
      put_le(&mat_bytes, r + spec::kImageMaterialIor, fmt.encode(m.ior), 4);
      put_le(&mat_bytes, r + spec::kImageMaterialEta, material_eta(fmt, fmt.encode(m.ior)), 4);
    }
  }

  std::vector<uint8_t> view(spec::kImageViewStride, 0);
  const Camera cam = scene.camera ? *scene.camera : auto_camera(root.lo, root.hi);
  for (int k = 0; k < 3; ++k) {
    put_f32(&view, spec::kImageViewEye + 4 * k, static_cast<float>(cam.eye[k]));
    put_f32(&view, spec::kImageViewLook + 4 * k, static_cast<float>(cam.look[k]));
    put_f32(&view, spec::kImageViewUp + 4 * k, static_cast<float>(cam.up[k]));
    put_f32(&view, spec::kImageViewBackground + 4 * k, static_cast<float>(scene.background[k]));
  }
  put_f32(&view, spec::kImageViewFov, static_cast<float>(cam.fov_deg));
  put_le(&view, spec::kImageViewWidth, scene.width, 4);
  put_le(&view, spec::kImageViewHeight, scene.height, 4);
  put_le(&view, spec::kImageViewFlags, scene.camera ? 0 : spec::kImageViewFlagAutoCamera, 4);

  std::vector<uint8_t> light_bytes(scene.lights.size() * spec::kImageLightStride, 0);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    const size_t r = i * spec::kImageLightStride;
    put_le(&light_bytes, r + spec::kImageLightType,
           l.type == Light::Type::kPoint ? spec::kImageLightTypePoint
                                         : spec::kImageLightTypeDirectional,
           4);
    for (int k = 0; k < 3; ++k) {
      put_f32(&light_bytes, r + spec::kImageLightPosition + 4 * k,
              static_cast<float>(l.position[k]));
      put_f32(&light_bytes, r + spec::kImageLightColor + 4 * k, static_cast<float>(l.color[k]));
    }
    put_f32(&light_bytes, r + spec::kImageLightIntensity, static_cast<float>(l.intensity));
  }

  const auto u32 = [](size_t v) { return static_cast<uint32_t>(v); };
  w.add_section(spec::kImageSectionIdNodes, std::move(node_bytes), u32(tree.nodes.size()),
                spec::kKdNodeBytes);
  w.add_section(spec::kImageSectionIdLists, std::move(list_bytes), u32(tree.lists.size()),
                spec::kKdListEntryBytes);
  w.add_section(spec::kImageSectionIdTriangles, std::move(tri_bytes), u32(nt), u32(tri_stride));
  w.add_section(spec::kImageSectionIdShading, std::move(shade_bytes), u32(nt), shade_stride);
  w.add_section(spec::kImageSectionIdMaterials, std::move(mat_bytes), u32(st.materials),
                spec::kImageMaterialStride);
  const size_t string_count = strings.size();
  w.add_section(spec::kImageSectionIdStrings, std::move(strings), u32(string_count), 1);
  w.add_section(spec::kImageSectionIdView, std::move(view), 1, spec::kImageViewStride);
  w.add_section(spec::kImageSectionIdLights, std::move(light_bytes), u32(scene.lights.size()),
                spec::kImageLightStride);
  out.image = w.finish();
  st.write_ms = ms_since(t0);

  // Statistics, read back from the image's own section table.
  const SceneImage img = SceneImage::from_bytes(out.image, scene.source);
  for (const auto& s : img.sections())
    st.sections.push_back({section_name(s.id), s.id, s.offset, s.bytes, s.count, s.stride});
  st.image_bytes = out.image.size();
  st.checksum = img.checksum();
  st.nodes = tree.nodes.size();
  st.inner = tree.inner;
  st.leaves = tree.leaves;
  st.empty_leaves = tree.empty_leaves;
  st.references = tree.lists.size();
  const size_t full = tree.leaves - tree.empty_leaves;
  st.mean_leaf = full ? static_cast<double>(tree.lists.size()) / static_cast<double>(full) : 0.0;
  st.max_leaf = tree.max_leaf;
  st.depth = tree.depth;
  st.sah_cost = tree.sah_cost;
  return out;
}

void print_stats(std::ostream& o, const BuildStats& s) {
  const auto fixed = [](double v, int prec) {
    std::ostringstream ss;
    ss << std::fixed << std::setprecision(prec) << v;
    return ss.str();
  };
  const size_t live = s.triangles - s.dropped;
  o << "scene        " << s.scene_name << " (" << s.input << ")\n";
  o << "format       " << s.format << "\n";
  o << "meshes       " << s.meshes << ", " << s.vertices << " vertices, " << s.materials
    << " materials, " << s.lights << " lights\n";
  o << "triangles    " << s.triangles << " (" << s.dropped << " dropped as degenerate, " << live
    << " in the tree)\n";
  o << "bounds       [" << num(s.bounds[0]) << ", " << num(s.bounds[1]) << ", " << num(s.bounds[2])
    << "] .. [" << num(s.bounds[3]) << ", " << num(s.bounds[4]) << ", " << num(s.bounds[5])
    << "]\n";
  o << "kd-tree      " << s.nodes << " nodes: " << s.inner << " inner, " << s.leaves << " leaves ("
    << s.empty_leaves << " empty)\n";
  o << "leaves       " << fixed(s.mean_leaf, 2) << " triangles per non-empty leaf on average, max "
    << s.max_leaf << "; " << s.references << " references ("
    << fixed(live ? static_cast<double>(s.references) / static_cast<double>(live) : 0.0, 2)
    << " per triangle)\n";
  o << "depth        " << s.depth << " (limit " << s.depth_limit << ")\n";
  o << "SAH cost     " << fixed(s.sah_cost, 2) << " (traversal " << spec::kKdtreeTraversalCost
    << ", intersection " << spec::kKdtreeIntersectionCost << " per triangle)\n";
  o << "sections     ";
  for (size_t i = 0; i < s.sections.size(); ++i) {
    const auto& sec = s.sections[i];
    if (i) o << "             ";
    o << std::left << std::setw(10) << sec.name << std::right << std::setw(10) << sec.bytes
      << " bytes  " << sec.count << " x " << sec.stride << " at " << sec.offset << "\n";
  }
  char crc[16];
  std::snprintf(crc, sizeof crc, "0x%08x", s.checksum);
  o << "image        " << s.image_bytes << " bytes, CRC-32 " << crc << "\n";
  o << "time         load " << fixed(s.load_ms, 1) << " ms, transforms " << fixed(s.transform_ms, 1)
    << " ms, kd-tree build " << fixed(s.build_ms, 1) << " ms, write " << fixed(s.write_ms, 1)
    << " ms\n";
}

nlohmann::json stats_to_json(const BuildStats& s) {
  nlohmann::json j;
  j["scene"] = s.scene_name;
  j["input"] = s.input;
  j["format"] = s.format;
  j["meshes"] = s.meshes;
  j["vertices"] = s.vertices;
  j["triangles"] = s.triangles;
  j["dropped_degenerate"] = s.dropped;
  j["materials"] = s.materials;
  j["lights"] = s.lights;
  j["bounds"] = {{"min", {s.bounds[0], s.bounds[1], s.bounds[2]}},
                 {"max", {s.bounds[3], s.bounds[4], s.bounds[5]}}};
  j["kdtree"] = {{"nodes", s.nodes},
                 {"inner", s.inner},
                 {"leaves", s.leaves},
                 {"empty_leaves", s.empty_leaves},
                 {"references", s.references},
                 {"mean_triangles_per_nonempty_leaf", s.mean_leaf},
                 {"max_triangles_per_leaf", s.max_leaf},
                 {"max_depth", s.depth},
                 {"depth_limit", s.depth_limit},
                 {"sah_cost", s.sah_cost},
                 {"traversal_cost", spec::kKdtreeTraversalCost},
                 {"intersection_cost", spec::kKdtreeIntersectionCost}};
  nlohmann::json secs = nlohmann::json::array();
  for (const auto& sec : s.sections)
    secs.push_back({{"name", sec.name},
                    {"id", sec.id},
                    {"offset", sec.offset},
                    {"bytes", sec.bytes},
                    {"count", sec.count},
                    {"stride", sec.stride}});
  j["sections"] = secs;
  j["image_bytes"] = s.image_bytes;
  char crc[16];
  std::snprintf(crc, sizeof crc, "0x%08x", s.checksum);
  j["checksum"] = crc;
  j["time_ms"] = {{"load", s.load_ms},
                  {"transforms", s.transform_ms},
                  {"build", s.build_ms},
                  {"write", s.write_ms}};
  j["warnings"] = s.warnings;
  return j;
}

}  // namespace rc::scene
