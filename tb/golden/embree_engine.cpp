#include "embree_engine.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/common.hpp>
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
    rtcSetSceneFlags(scene, static_cast<RTCSceneFlags>(RTC_SCENE_FLAG_ROBUST |
                                                       RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
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

// A shadow ray's context: the triangle it starts on never occludes it.
struct ShadowContext {
  RTCIntersectContext ctx;  // first: Embree passes &ctx to the filter
  unsigned exclude;
};

void exclude_start(const RTCFilterFunctionNArguments* args) {
  const auto* sc = reinterpret_cast<const ShadowContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] != 0 && RTCHitN_primID(args->hit, args->N, i) == sc->exclude)
      args->valid[i] = 0;
}

struct LitResult {
  std::array<uint8_t, 3> rgb;
  uint32_t lights;
  int32_t bounce_tri;   // the first mirror ray's hit: -2 none, -1 a miss
  int32_t refract_tri;  // the first refraction ray's hit: -2 none, -1 a miss
};

// The lighting rules in double (docs/architecture.md, "Lighting", "Reflection" and
// "Refraction"), shadow, mirror and refraction rays through Embree in float32.
struct LitTracer {
  const EmbreeScene& es;
  const std::vector<SoupTriangle>& tris;
  const std::vector<SoupLight>& lights;
  double t_eps;
  uint32_t max_bounces;
  glm::dvec3 background;  // byte / 255

  // Adds the terms of a hit (triangle prim at distance t along org + t * dir) seen with weight w
  // at depth `depth` to sum; *lit gets the lights that reach it, *bounce_tri and *refract_tri the
  // hits of its mirror and refraction rays (the primary hit's).
  void shade(unsigned prim, const glm::dvec3& org, const glm::dvec3& dir, double t, double w,
             uint32_t depth, glm::dvec3& sum, uint32_t* lit, int32_t* bounce_tri,
             int32_t* refract_tri) const {
    const SoupTriangle& tri = tris[prim];
    const double ambient = static_cast<double>(spec::kShadeAmbientPermille) / 1000.0;
    const glm::dvec3 p = org + t * dir;
    glm::dvec3 n = glm::normalize(glm::cross(tri.v[1] - tri.v[0], tri.v[2] - tri.v[0]));
    const bool leaving = glm::dot(n, dir) > 0.0;  // the ray travels along n: it leaves the medium
    if (leaving) n = -n;
    const glm::dvec3 v = glm::normalize(dir);
    const uint32_t ns = light_exponent(fp32ftz::from_double(tri.ns));
    for (int c = 0; c < 3; ++c) sum[c] += std::clamp(tri.kd[c] * ambient * w, 0.0, 1.0);
    for (size_t li = 0; li < lights.size(); ++li) {
      const SoupLight& l = lights[li];
      glm::dvec3 lh = l.pos;
      double dist = std::numeric_limits<double>::infinity();
      if (!l.directional) {
        const glm::dvec3 d = l.pos - p;
        dist = glm::length(d);
        lh = d / dist;
      }
      const double cos_l = glm::dot(n, lh);
      if (!(cos_l > 0.0)) continue;
      ShadowContext sc;
      rtcInitIntersectContext(&sc.ctx);
      sc.ctx.filter = exclude_start;
      sc.exclude = prim;
      RTCRay ray = embree_ray(p, lh, dist);
      rtcOccluded1(es.scene, &sc.ctx, &ray);
      if (ray.tfar < 0.0f) continue;  // occluded: Embree sets tfar to -inf
      if (lit && li < 32) *lit |= 1u << li;
      const glm::dvec3 h = glm::normalize(lh - v);
      const double nh = glm::dot(n, h);
      const double spec = nh > 0.0 ? std::pow(nh, static_cast<double>(ns)) : 0.0;
      for (int c = 0; c < 3; ++c)
        sum[c] += std::clamp((tri.kd[c] * cos_l + tri.ks[c] * spec) * l.color[c] * w, 0.0, 1.0);
    }
    if (depth >= max_bounces) return;
    // The mirror ray: R = V - 2 (N . V) N from the hit point, closest hit beyond t_eps.
    const double c = glm::dot(n, v);
    const double wm = w * tri.mirror;
    if (tri.mirror > 0.0 && wm > 0.0) follow(prim, p, v - 2.0 * c * n, wm, depth, sum, bounce_tri);
    // The refraction ray (Snell, e = ior leaving, 1 / ior entering; total internal reflection
    // takes the mirror direction).
    const double wt = w * tri.transmit;
    if (tri.transmit > 0.0 && wt > 0.0) {
      const double e = leaving ? tri.ior : 1.0 / tri.ior;
      const double q = 1.0 - e * e * (1.0 - c * c);
      const glm::dvec3 d = q > 0.0 ? e * v - (e * c + std::sqrt(q)) * n : v - 2.0 * c * n;
      follow(prim, p, d, wt, depth, sum, refract_tri);
    }
  }

  // A mirror or refraction ray from the hit point p on triangle prim along d (unit) with weight w:
  // its closest hit beyond t_eps adds its terms at depth + 1; a miss, the background.
  void follow(unsigned prim, const glm::dvec3& p, const glm::dvec3& d, double w, uint32_t depth,
              glm::dvec3& sum, int32_t* first_tri) const {
    ShadowContext sc;
    rtcInitIntersectContext(&sc.ctx);
    sc.ctx.filter = exclude_start;
    sc.exclude = prim;
    RTCRayHit rh{};
    rh.ray = embree_ray(p, d, std::numeric_limits<double>::infinity());
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(es.scene, &sc.ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      if (first_tri) *first_tri = -1;
      for (int c = 0; c < 3; ++c) sum[c] += std::clamp(background[c] * w, 0.0, 1.0);
      return;
    }
    if (first_tri) *first_tri = static_cast<int32_t>(rh.hit.primID);
    const glm::dvec3 ro(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z);
    const glm::dvec3 rd(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
    shade(rh.hit.primID, ro, rd, rh.ray.tfar, w, depth + 1, sum, nullptr, nullptr, nullptr);
  }

  // A float32 ray from p along d (unit) beyond t_eps, up to tfar.
  RTCRay embree_ray(const glm::dvec3& p, const glm::dvec3& d, double tfar) const {
    RTCRay ray{};
    ray.org_x = static_cast<float>(p.x);
    ray.org_y = static_cast<float>(p.y);
    ray.org_z = static_cast<float>(p.z);
    ray.dir_x = static_cast<float>(d.x);
    ray.dir_y = static_cast<float>(d.y);
    ray.dir_z = static_cast<float>(d.z);
    ray.tnear = static_cast<float>(t_eps);
    ray.tfar = static_cast<float>(tfar);
    ray.mask = 0xffffffffu;
    return ray;
  }

  LitResult primary(unsigned prim, const glm::dvec3& org, const glm::dvec3& dir, double t) const {
    glm::dvec3 sum(0.0);
    LitResult out{{0, 0, 0}, 0, -2, -2};
    shade(prim, org, dir, t, 1.0, 0, sum, &out.lights, &out.bounce_tri, &out.refract_tri);
    for (int c = 0; c < 3; ++c)
      out.rgb[c] = static_cast<uint8_t>(std::nearbyint(std::min(sum[c], 1.0) * 255.0));
    return out;
  }
};

}  // namespace

template <class T>
Frame render_embree(const std::vector<SoupTriangle>& tris, const RenderOptions& opt,
                    const std::vector<SoupLight>& lights) {
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
  const bool lit = opt.lighting == Lighting::kScene && !lights.empty();
  double t_eps = 0.0;
  if (lit) {
    f.light_mask.assign(npix, 0);
    f.bounce_tri.assign(npix, -2);
    f.refract_tri.assign(npix, -2);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const auto& t : tris)
      for (const auto& v : t.v) lo = glm::min(lo, v), hi = glm::max(hi, v);
    t_eps = tris.empty() ? 0.0 : glm::length(hi - lo) * kShadowEpsScale;
  }
  LitTracer tracer{es, tris, lights, t_eps, opt.max_bounces, glm::dvec3(0.0)};
  for (int c = 0; c < 3; ++c) tracer.background[c] = opt.background[c] / 255.0;
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
        const glm::dvec3 dir(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
        if (lit) {
          const glm::dvec3 org(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z);
          const LitResult lr = tracer.primary(rh.hit.primID, org, dir, rh.ray.tfar);
          rgb = lr.rgb;
          f.light_mask[pix] = lr.lights;
          f.bounce_tri[pix] = lr.bounce_tri;
          f.refract_tri[pix] = lr.refract_tri;
        } else {
          rgb = shade_double(tris[rh.hit.primID], dir);
        }
      }
      std::memcpy(&f.rgb[pix * 3], rgb.data(), 3);
    }
  });
  f.counters.rays = npix;
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return f;
}

template Frame render_embree<fp24>(const std::vector<SoupTriangle>&, const RenderOptions&,
                                   const std::vector<SoupLight>&);
template Frame render_embree<fp32ftz>(const std::vector<SoupTriangle>&, const RenderOptions&,
                                      const std::vector<SoupLight>&);

}  // namespace rc
