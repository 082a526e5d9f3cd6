// Frame rendering on top of the golden model: packets as 2x2 pixel quads, multithreaded over
// rows of packets, deterministic whatever the thread count.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "camera.hpp"
#include "trace.hpp"

namespace rc {

// One pixel's closest hit exactly, as the core's framebuffer port reports it: the triangle and
// the format bit patterns of t, u and v (all zero, tri -1, for a miss).
struct HitRecord {
  int32_t tri = -1;
  uint32_t t = 0, u = 0, v = 0;
  bool operator==(const HitRecord& o) const {
    return tri == o.tri && t == o.t && u == o.u && v == o.v;
  }
  bool operator!=(const HitRecord& o) const { return !(*this == o); }
};

// Per pixel: what the hits file stores, plus the shaded colour.
struct Frame {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgb;      // width * height * 3, top row first
  std::vector<int32_t> hit_tri;  // -1 for a miss
  std::vector<float> hit_t;      // hit distance (0 for a miss)
  std::vector<HitRecord> hits;   // exact hit records (golden model and RTL; empty for Embree)
  // Scene lighting: per pixel, bit l set when light l reaches the hit (in front of the surface
  // and unoccluded; lights 0 to 31); empty with the headlight.
  std::vector<uint32_t> light_mask;
  // Scene lighting: per pixel, the triangle its first mirror ray hits (-1: it missed or its
  // packet failed; -2: the pixel has no mirror ray); empty with the headlight.
  std::vector<int32_t> bounce_tri;
  // Scene lighting: the same for the pixel's refraction ray.
  std::vector<int32_t> refract_tri;
  Counters counters;          // primary rays
  Counters shadow_counters;   // shadow rays (scene lighting)
  Counters bounce_counters;   // mirror rays (scene lighting)
  Counters refract_counters;  // refraction rays (scene lighting)
  double seconds = 0.0;
};

// Where the rays come from (docs/architecture.md, "Two ray sources"): the host's double-precision
// camera rounded once (the packet port's rays), or the board's ray generation unit.
enum class RaySource { kHost, kRayGen };
RaySource parse_ray_source(const std::string& name);  // "host" | "raygen"; throws otherwise
const char* ray_source_name(RaySource s);

// How hits are shaded (docs/architecture.md, "Shading" and "Lighting"): the headlight (the
// core's rule today), or the scene's lights with shadow, mirror and refraction rays (a scene
// without lights keeps the headlight).
enum class Lighting { kHeadlight, kScene };
Lighting parse_lighting(const std::string& name);  // "headlight" | "scene"; throws otherwise
const char* lighting_name(Lighting l);

// The most threads a render takes (the command line's --threads bound).
constexpr unsigned kMaxRenderThreads = 256;

struct RenderOptions {
  uint32_t width = 256, height = 192;
  Camera camera;
  std::array<uint8_t, 3> background{0, 0, 0};
  unsigned threads = 0;  // 0: all hardware threads; at most kMaxRenderThreads
  bool progress = true;  // progress bar on stderr for renders longer than a second
  RaySource ray_source = RaySource::kHost;
  Lighting lighting = Lighting::kHeadlight;
  // Scene lighting: the depth of a pixel's ray tree (docs/architecture.md, "Reflection" and
  // "Refraction"); 0: no mirror or refraction rays. At most spec::kLightBounceLimit.
  uint32_t max_bounces = static_cast<uint32_t>(spec::kLightMaxBounces);
};

// A generated ray as the core sees it: each component rounded to the format once.
template <class T>
Ray<T> core_ray(const RayD& d) {
  Ray<T> r;
  for (int a = 0; a < 3; ++a) {
    r.org[a] = T::from_double(d.org[a]);
    r.dir[a] = T::from_double(d.dir[a]);
  }
  r.inv_len = T::from_double(d.inv_len);
  return r;
}

// The ray generation unit's registers in the format (each rounded once from double).
template <class T>
struct CameraRegisters {
  std::array<T, 3> eye, c0, cx, cy;
};

template <class T>
CameraRegisters<T> round_registers(const CameraRegistersD& d) {
  CameraRegisters<T> c;
  for (int a = 0; a < 3; ++a) {
    c.eye[a] = T::from_double(d.eye[a]);
    c.c0[a] = T::from_double(d.c0[a]);
    c.cx[a] = T::from_double(d.cx[a]);
    c.cy[a] = T::from_double(d.cy[a]);
  }
  return c;
}

// The ray of pixel (x, y) exactly as rtl/board/rc_ray_gen.sv computes it, in format operations
// in the order of docs/architecture.md ("Two ray sources").
template <class T>
Ray<T> raygen_ray(const CameraRegisters<T>& c, uint32_t x, uint32_t y) {
  const T fx = T::from_double(static_cast<double>(x));  // exact below 2^(F+1)
  const T fy = T::from_double(static_cast<double>(y));
  Ray<T> r;
  for (int a = 0; a < 3; ++a) {
    r.org[a] = c.eye[a];
    r.dir[a] = (c.c0[a] + fx * c.cx[a]) + fy * c.cy[a];
  }
  const auto& d = r.dir;
  r.inv_len = T::one() / sqrt((d[0] * d[0] + d[1] * d[1]) + d[2] * d[2]);
  return r;
}

// The rays of a frame from either source, by pixel and by packet.
template <class T>
class PacketSource {
 public:
  PacketSource(const Camera& cam, uint32_t width, uint32_t height, RaySource src)
      : gen_(cam, width, height),
        regs_(round_registers<T>(camera_registers(cam, width, height))),
        src_(src) {
    if (width >= (1u << (T::kFracW + 1)) || height >= (1u << (T::kFracW + 1)))
      throw std::runtime_error("image size too large for the format's exact pixel coordinates");
  }
  Ray<T> ray(uint32_t x, uint32_t y) const {
    return src_ == RaySource::kHost ? core_ray<T>(gen_.ray(x, y)) : raygen_ray(regs_, x, y);
  }
  // The four rays of packet (px, py): pixels (2px + (r & 1), 2py + (r >> 1)) for r = 0..3; a ray
  // whose pixel lies outside the image is absent (its mask bit is 0). Returns the mask.
  uint32_t packet(uint32_t px, uint32_t py, std::array<Ray<T>, kPacketRays>& rays) const {
    uint32_t mask = 0;
    for (int r = 0; r < kPacketRays; ++r) {
      const uint32_t x = 2 * px + (static_cast<uint32_t>(r) & 1u);
      const uint32_t y = 2 * py + (static_cast<uint32_t>(r) >> 1);
      if (x >= width() || y >= height()) continue;
      rays[r] = ray(x, y);
      mask |= 1u << r;
    }
    return mask;
  }
  uint32_t width() const { return gen_.width(); }
  uint32_t height() const { return gen_.height(); }
  RaySource source() const { return src_; }
  const CameraRegisters<T>& registers() const { return regs_; }

 private:
  RayGenerator gen_;
  CameraRegisters<T> regs_;
  RaySource src_;
};

// Runs fn(row) for every row of [0, rows) on `threads` threads (0: all hardware threads), with a
// progress bar on stderr when `progress` and the work takes longer than a second. Threads that
// cannot be started leave their rows to the others; an exception thrown by fn stops the work and
// is rethrown once every thread has joined.
void parallel_rows(uint32_t rows, unsigned threads, bool progress, const char* label,
                   const std::function<void(uint32_t)>& fn);

template <class T>
Frame render_golden(const Geometry<T>& g, const RenderOptions& opt);

// Writes the hits file: "RCHITS1\0", uint32 width, uint32 height, then per pixel (top row first)
// int32 triangle index (-1: miss) and float32 t, little-endian.
void write_hits(const std::string& path, const Frame& f);

}  // namespace rc
