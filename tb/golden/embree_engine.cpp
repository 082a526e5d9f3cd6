#include "embree_engine.hpp"

#include <embree3/rtcore.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <limits>
#include <stdexcept>

namespace rc {

std::array<uint8_t, 3> shade_double(const SoupTriangle& tri, const glm::dvec3& dir) {
  const double ambient = static_cast<double>(spec::kShadeAmbientPermille) / 1000.0;
  const glm::dvec3 n = glm::cross(tri.v[1] - tri.v[0], tri.v[2] - tri.v[0]);
  const double denom = glm::length(n) * glm::length(dir);
  const double c = denom > 0.0 ? std::min(std::fabs(glm::dot(n, dir)) / denom, 1.0) : 0.0;
  const double f = ambient + (1.0 - ambient) * c;
  std::array<uint8_t, 3> out{};
  for (int i = 0; i < 3; ++i)
    out[i] = static_cast<uint8_t>(std::nearbyint(std::clamp(tri.kd[i] * f, 0.0, 1.0) * 255.0));
  return out;
}

namespace {

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit EmbreeScene(const std::vector<SoupTriangle>& tris) {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("embree: cannot create a device");
    scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * tris.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
    if (!vb || !ib) throw std::runtime_error("embree: cannot allocate geometry buffers");
    for (size_t i = 0; i < tris.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 3; ++a) vb[9 * i + 3 * k + a] = static_cast<float>(tris[i].v[k][a]);
        ib[3 * i + k] = static_cast<unsigned>(3 * i + k);
      }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
  }
  ~EmbreeScene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
};

}  // namespace

template <class T>
Frame render_embree(const std::vector<SoupTriangle>& tris, const RenderOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const EmbreeScene es(tris);
  const PacketSource<T> gen(opt.camera, opt.width, opt.height, opt.ray_source);
  Frame f;
  f.width = opt.width;
  f.height = opt.height;
  const size_t npix = static_cast<size_t>(opt.width) * opt.height;
  f.rgb.assign(npix * 3, 0);
  f.hit_tri.assign(npix, -1);
  f.hit_t.assign(npix, 0.0f);
  parallel_rows(opt.height, opt.threads, opt.progress, "embree", [&](uint32_t y) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (uint32_t x = 0; x < opt.width; ++x) {
      const Ray<T> cr = gen.ray(x, y);  // widened to float32 exactly below
      RTCRayHit rh{};
      rh.ray.org_x = cr.org[0].to_float();
      rh.ray.org_y = cr.org[1].to_float();
      rh.ray.org_z = cr.org[2].to_float();
      rh.ray.dir_x = cr.dir[0].to_float();
      rh.ray.dir_y = cr.dir[1].to_float();
      rh.ray.dir_z = cr.dir[2].to_float();
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.mask = 0xffffffffu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(es.scene, &ctx, &rh);
      const size_t pix = static_cast<size_t>(y) * opt.width + x;
      std::array<uint8_t, 3> rgb = opt.background;
      if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        f.hit_tri[pix] = static_cast<int32_t>(rh.hit.primID);
        f.hit_t[pix] = rh.ray.tfar;
        rgb =
            shade_double(tris[rh.hit.primID], glm::dvec3(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z));
      }
      std::memcpy(&f.rgb[pix * 3], rgb.data(), 3);
    }
  });
  f.counters.rays = npix;
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return f;
}

template Frame render_embree<fp24>(const std::vector<SoupTriangle>&, const RenderOptions&);
template Frame render_embree<fp32ftz>(const std::vector<SoupTriangle>&, const RenderOptions&);

}  // namespace rc
