#include "render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace rc {

void parallel_rows(uint32_t rows, unsigned threads, bool progress, const char* label,
                   const std::function<void(uint32_t)>& fn) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  std::atomic<uint32_t> next{0}, done{0};
  const auto start = std::chrono::steady_clock::now();
  std::mutex print_mutex;
  bool printed = false;
  const auto worker = [&] {
    for (uint32_t row; (row = next.fetch_add(1)) < rows;) {
      fn(row);
      const uint32_t d = done.fetch_add(1) + 1;
      if (!progress) continue;
      const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (s < 1.0 || (d % 8 != 0 && d != rows)) continue;
      std::lock_guard<std::mutex> lock(print_mutex);
      const int bar = static_cast<int>(40.0 * d / rows);
      std::fprintf(stderr, "\r%s [%-40.*s] %3u%% %.1fs", label, bar,
                   "########################################", 100u * d / rows, s);
      printed = true;
    }
  };
  // An exception in a row (a worker's or this thread's) ends the work and is rethrown here after
  // every thread has joined; a thread that cannot be started leaves the rows to the others.
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto guarded = [&] {
    try {
      worker();
    } catch (...) {
      next.store(rows);
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  try {
    pool.reserve(threads - 1);
    for (unsigned i = 1; i < threads; ++i) pool.emplace_back(guarded);
  } catch (const std::exception&) {  // std::system_error (no more threads) or bad_alloc
  }
  guarded();
  for (auto& t : pool) t.join();
  if (printed) std::fprintf(stderr, "\n");
  if (failure) std::rethrow_exception(failure);
}

template <class T>
Frame render_golden(const Geometry<T>& g, const RenderOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const PacketSource<T> gen(opt.camera, opt.width, opt.height, opt.ray_source);
  Frame f;
  f.width = opt.width;
  f.height = opt.height;
  f.rgb.assign(static_cast<size_t>(opt.width) * opt.height * 3, 0);
  f.hit_tri.assign(static_cast<size_t>(opt.width) * opt.height, -1);
  f.hit_t.assign(static_cast<size_t>(opt.width) * opt.height, 0.0f);
  f.hits.assign(static_cast<size_t>(opt.width) * opt.height, HitRecord{});
  const bool lit = opt.lighting == Lighting::kScene && !g.lights.empty();
  if (lit) {
    f.light_mask.assign(static_cast<size_t>(opt.width) * opt.height, 0);
    f.bounce_tri.assign(static_cast<size_t>(opt.width) * opt.height, -2);
    f.refract_tri.assign(static_cast<size_t>(opt.width) * opt.height, -2);
  }
  const uint32_t pw = (opt.width + 1) / 2, ph = (opt.height + 1) / 2;
  std::vector<Counters> row_counters(ph);
  std::vector<LitCounters> row_lit(ph);
  const LitParams<T> lparams = lit_params<T>(opt.max_bounces, opt.background);
  parallel_rows(ph, opt.threads, opt.progress, "golden", [&](uint32_t py) {
    Counters& c = row_counters[py];
    std::array<Ray<T>, kPacketRays> rays;
    std::array<Hit<T>, kPacketRays> hits;
    for (uint32_t px = 0; px < pw; ++px) {
      const uint32_t mask = gen.packet(px, py, rays);
      trace_packet(g, rays, mask, hits, c);  // errors are counted in c
      LitPacket lp;
      if (lit) lp = shade_lit(g, rays, mask, hits, lparams, row_lit[py]);
      for (int r = 0; r < kPacketRays; ++r) {
        if (!(mask >> r & 1)) continue;
        const size_t pix =
            static_cast<size_t>(2 * py + (static_cast<uint32_t>(r) >> 1)) * opt.width + 2 * px +
            (static_cast<uint32_t>(r) & 1u);
        const auto& h = hits[r];
        const std::array<uint8_t, 3> rgb = h.tri < 0 ? opt.background
                                           : lit     ? lp.rgb[r]
                                                     : shade(g, rays[r], h);
        if (lit) {
          f.light_mask[pix] = lp.lights[r];
          f.bounce_tri[pix] = lp.bounce_tri[r];
          f.refract_tri[pix] = lp.refract_tri[r];
        }
        std::memcpy(&f.rgb[pix * 3], rgb.data(), 3);
        f.hit_tri[pix] = h.tri;
        f.hit_t[pix] = h.tri >= 0 ? h.t.to_float() : 0.0f;
        if (h.tri >= 0) f.hits[pix] = HitRecord{h.tri, h.t.bits(), h.u.bits(), h.v.bits()};
      }
    }
  });
  for (const Counters& c : row_counters) f.counters.add(c);  // in row order: same totals always
  for (const LitCounters& c : row_lit) {
    f.shadow_counters.add(c.shadow);
    f.bounce_counters.add(c.bounce);
    f.refract_counters.add(c.refract);
  }
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return f;
}

template Frame render_golden<fp24>(const Geometry<fp24>&, const RenderOptions&);
template Frame render_golden<fp32ftz>(const Geometry<fp32ftz>&, const RenderOptions&);

Lighting parse_lighting(const std::string& name) {
  if (name == "headlight") return Lighting::kHeadlight;
  if (name == "scene") return Lighting::kScene;
  throw std::runtime_error("unknown lighting '" + name + "' (headlight, scene)");
}

const char* lighting_name(Lighting l) { return l == Lighting::kHeadlight ? "headlight" : "scene"; }

RaySource parse_ray_source(const std::string& name) {
  if (name == "host") return RaySource::kHost;
  if (name == "raygen") return RaySource::kRayGen;
  throw std::runtime_error("unknown ray source '" + name + "' (host, raygen)");
}

const char* ray_source_name(RaySource s) { return s == RaySource::kHost ? "host" : "raygen"; }

namespace {
void put_u32(std::ofstream& out, uint32_t v) {
  const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                              static_cast<unsigned char>(v >> 16),
                              static_cast<unsigned char>(v >> 24)};
  out.write(reinterpret_cast<const char*>(b), 4);
}
}  // namespace

void write_hits(const std::string& path, const Frame& f) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write hits file '" + path + "'");
  out.write("RCHITS1\0", 8);
  put_u32(out, f.width);
  put_u32(out, f.height);
  for (size_t i = 0; i < f.hit_tri.size(); ++i) {
    put_u32(out, static_cast<uint32_t>(f.hit_tri[i]));
    uint32_t tb;
    std::memcpy(&tb, &f.hit_t[i], 4);
    put_u32(out, tb);
  }
  if (!out) throw std::runtime_error("error writing hits file '" + path + "'");
}

}  // namespace rc
