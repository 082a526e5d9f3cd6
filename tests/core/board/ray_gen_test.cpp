// The ray generation unit (rtl/board/rc_ray_gen.sv), verilated at both periods (3, and 6 with its
// shared operators), against the golden second ray source (rc::raygen_ray(), rc::PacketSource
// with RaySource::kRayGen in tb/golden/render.hpp): every packet of a frame, in order, with its
// mask, pixel ids and every ray's origin, direction and inv_len bit for bit, under seeded random
// back-pressure on the packet port. Cameras from real scenes, odd and tiny frame sizes, and random
// register contents (special values included).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <type_traits>

#include "Vrc_ray_gen_p3.h"
#include "Vrc_ray_gen_p6.h"
#include "camera.hpp"
#include "render.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::get_field;
using rc::harness::put_field;
using rc::harness::VerilatedTb;

namespace {

constexpr unsigned kW = fp24::kWidth;

// A field of a port (fp24 words and pixel ids, placed by unsigned offsets).
template <class P>
void put(P& port, unsigned lsb, uint32_t value) {
  put_field(port, static_cast<int>(lsb), static_cast<int>(kW), value);
}
template <class P>
uint32_t get(const P& port, unsigned lsb, unsigned width) {
  return static_cast<uint32_t>(get_field(port, static_cast<int>(lsb), static_cast<int>(width)));
}

struct Frame {
  CameraRegisters<fp24> regs;
  uint32_t width, height;
};

struct Outcome {
  uint64_t packets = 0, rays = 0, mismatches = 0;
};

// Runs one frame through the unit M and checks every packet. stall: probability that pkt_ready_i
// is low in a cycle.
template <class M>
Outcome run_frame(const Frame& fr, double stall, uint64_t seed) {
  // Not fatal on error: a failing RTL assertion fails the test (the wrapper's TbError).
  VerilatedTb<M> tb("ray_gen", false);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution low(stall);
  const auto tick = [&] { tb.tick(); };
  for (unsigned a = 0; a < 3; ++a) {
    put(tb->eye_i, a * kW, fr.regs.eye[a].bits());
    put(tb->c0_i, a * kW, fr.regs.c0[a].bits());
    put(tb->cx_i, a * kW, fr.regs.cx[a].bits());
    put(tb->cy_i, a * kW, fr.regs.cy[a].bits());
  }
  tb->width_i = static_cast<uint16_t>(fr.width);
  tb->height_i = static_cast<uint16_t>(fr.height);
  tb->start_i = 0;
  tb->pkt_ready_i = 0;
  tb.reset(2);
  tick();
  tb->start_i = 1;
  tick();
  tb->start_i = 0;

  Outcome out;
  const uint32_t pw = (fr.width + 1) / 2, ph = (fr.height + 1) / 2;
  const uint64_t total = static_cast<uint64_t>(pw) * ph;
  const auto fail = [&](const std::string& what) {
    if (++out.mismatches <= 5) ADD_FAILURE() << what;
  };
  uint64_t cycles = 0;
  while (out.packets < total && cycles < 200 * (total + 100)) {
    const bool ready = !low(rng);
    tb->pkt_ready_i = ready;
    tb->eval();
    if (tb->pkt_valid_o && ready) {
      const uint32_t px = static_cast<uint32_t>(out.packets % pw),
                     py = static_cast<uint32_t>(out.packets / pw);
      uint32_t want_mask = 0;
      for (unsigned r = 0; r < 4; ++r) {
        const uint32_t x = 2 * px + (r & 1u), y = 2 * py + (r >> 1);
        if (x >= fr.width || y >= fr.height) continue;
        want_mask |= 1u << r;
        const Ray<fp24> ray = raygen_ray(fr.regs, x, y);
        const std::string where = "packet (" + std::to_string(px) + ", " + std::to_string(py) +
                                  ") ray " + std::to_string(r) + ": ";
        for (unsigned a = 0; a < 3; ++a) {
          const uint32_t org = get(tb->pkt_org_o, (3 * r + a) * kW, kW);
          const uint32_t dir = get(tb->pkt_dir_o, (3 * r + a) * kW, kW);
          if (org != ray.org[a].bits()) fail(where + "org " + fp24::from_bits(org).hex());
          if (dir != ray.dir[a].bits())
            fail(where + "dir[" + std::to_string(a) + "] rtl " + fp24::from_bits(dir).hex() +
                 ", model " + ray.dir[a].hex());
        }
        const uint32_t inv = get(tb->pkt_inv_len_o, r * kW, kW);
        if (inv != ray.inv_len.bits())
          fail(where + "inv_len rtl " + fp24::from_bits(inv).hex() + ", model " +
               ray.inv_len.hex());
        const uint32_t pix = get(tb->pkt_pixel_o, r * 32, 32);
        if (pix != y * fr.width + x) fail(where + "pixel id " + std::to_string(pix));
        ++out.rays;
      }
      if (tb->pkt_mask_o != want_mask)
        fail("packet " + std::to_string(out.packets) + ": mask " + std::to_string(tb->pkt_mask_o) +
             ", want " + std::to_string(want_mask));
      ++out.packets;
    }
    tick();
    ++cycles;
  }
  EXPECT_EQ(out.packets, total) << "packets missing after " << cycles << " cycles";
  tb->pkt_ready_i = 1;
  for (int i = 0; i < 4; ++i) {
    tb->eval();
    EXPECT_FALSE(tb->pkt_valid_o) << "a packet beyond the frame";
    tick();
  }
  EXPECT_FALSE(tb->busy_o) << "busy_o after the frame's last packet";
  return out;
}

Frame camera_frame(const Camera& cam, uint32_t w, uint32_t h) {
  return {round_registers<fp24>(camera_registers(cam, w, h)), w, h};
}

// The unit at each period (the models' -GPeriod): a test suite per model.
template <class M>
constexpr unsigned kPeriod = std::is_same_v<M, Vrc_ray_gen_p3> ? 3 : 6;
template <class M>
class RayGenRtl : public ::testing::Test {};
using RayGenModels = ::testing::Types<Vrc_ray_gen_p3, Vrc_ray_gen_p6>;
struct RayGenNames {
  template <class M>
  static std::string GetName(int) {
    return "Period" + std::to_string(kPeriod<M>);
  }
};
TYPED_TEST_SUITE(RayGenRtl, RayGenModels, RayGenNames);

template <class M>
void report(const std::string& what, const Outcome& o) {
  std::printf("[cases] ray_gen rtl period %u: %s: %llu cases, %llu mismatches (%llu packets)\n",
              kPeriod<M>, what.c_str(), static_cast<unsigned long long>(o.rays),
              static_cast<unsigned long long>(o.mismatches),
              static_cast<unsigned long long>(o.packets));
  EXPECT_EQ(o.mismatches, 0u);
}

Camera test_camera() {
  Camera c;
  c.eye = {0.3, 1.1, 3.8};
  c.look = {0.0, 0.9, 0.0};
  c.up = {0.0, 1.0, 0.0};
  c.fov_deg = 39.3;
  return c;
}

TYPED_TEST(RayGenRtl, CameraFrames) {
  Outcome all;
  const Camera cam = test_camera();
  const std::array<std::array<uint32_t, 2>, 5> sizes = {
      {{64, 48}, {33, 17}, {1, 1}, {2, 7}, {129, 3}}};
  uint64_t seed = 1;
  for (const auto& s : sizes)
    for (double stall : {0.0, 0.4}) {
      const Outcome o = run_frame<TypeParam>(camera_frame(cam, s[0], s[1]), stall, seed++);
      all.packets += o.packets;
      all.rays += o.rays;
      all.mismatches += o.mismatches;
    }
  report<TypeParam>("camera frames (64x48, 33x17, 1x1, 2x7, 129x3; no stalls and 40% stalls)", all);
}

TYPED_TEST(RayGenRtl, WideAngleAndOddCameras) {
  Outcome all;
  Camera c = test_camera();
  uint64_t seed = 10;
  for (double fov : {1.0, 90.0, 170.0})
    for (const auto& up : {glm::dvec3{0, 1, 0}, glm::dvec3{0.3, -1, 0.2}}) {
      c.fov_deg = fov;
      c.up = up;
      c.eye = {-2e3, 5e-3, 7.5};
      const Outcome o = run_frame<TypeParam>(camera_frame(c, 40, 30), 0.25, seed++);
      all.packets += o.packets;
      all.rays += o.rays;
      all.mismatches += o.mismatches;
    }
  report<TypeParam>("fov 1, 90, 170 degrees, tilted up vectors, far eye (40x30, 25% stalls)", all);
}

// Register contents no camera produces: random bit patterns, including zeros, infinities and
// NaNs, so the unit's special-value paths (and the format's) are exercised.
TYPED_TEST(RayGenRtl, RandomRegisters) {
  Outcome all;
  std::mt19937_64 rng(7);
  const std::array<uint32_t, 6> specials = {0x000000u, 0x800000u, 0x7f0000u,
                                            0xff0000u, 0x7f8000u, 0x3f0000u};
  const auto value = [&] {
    const uint32_t r = static_cast<uint32_t>(rng());
    if ((r & 7u) == 0) return fp24::from_bits(specials[(r >> 3) % specials.size()]);
    // Moderate exponents mostly, so sums and squares stay finite often.
    const uint32_t e = 0x3f - 12 + ((r >> 8) % 24);
    return fp24::from_bits(((r >> 31) << 23) | (e << 16) |
                           (static_cast<uint32_t>(rng()) & 0xffffu));
  };
  for (int k = 0; k < 12; ++k) {
    Frame fr;
    for (unsigned a = 0; a < 3; ++a) {
      fr.regs.eye[a] = value();
      fr.regs.c0[a] = value();
      fr.regs.cx[a] = value();
      fr.regs.cy[a] = value();
    }
    fr.width = 1 + static_cast<uint32_t>(rng() % 37);
    fr.height = 1 + static_cast<uint32_t>(rng() % 29);
    const Outcome o = run_frame<TypeParam>(fr, (k % 3) * 0.3, 100 + static_cast<uint64_t>(k));
    all.packets += o.packets;
    all.rays += o.rays;
    all.mismatches += o.mismatches;
  }
  report<TypeParam>("random registers with special values (12 frames up to 37x29, 0-60% stalls)",
                    all);
}

TYPED_TEST(RayGenRtl, EmptyFrameEndsAtOnce) {
  Frame fr = camera_frame(test_camera(), 8, 8);
  fr.width = 0;
  const Outcome o = run_frame<TypeParam>(fr, 0.0, 5);
  EXPECT_EQ(o.packets, 0u);
  fr.width = 8;
  fr.height = 0;
  EXPECT_EQ(run_frame<TypeParam>(fr, 0.0, 6).packets, 0u);
}

// The second ray source is close to the first: the fp24 arithmetic of the ray generation unit
// against the double-precision camera rounded once (a plausibility check of the registers, not a
// bit-exact one).
TEST(RayGenModel, CloseToTheHostRays) {
  const Camera cam = test_camera();
  const PacketSource<fp24> host(cam, 64, 48, RaySource::kHost);
  const PacketSource<fp24> gen(cam, 64, 48, RaySource::kRayGen);
  double worst_dir = 0, worst_inv = 0;
  for (uint32_t y = 0; y < 48; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      const Ray<fp24> a = host.ray(x, y), b = gen.ray(x, y);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(a.org[k].bits(), b.org[k].bits());
        const double d = std::abs(a.dir[k].to_double() - b.dir[k].to_double());
        worst_dir = std::max(worst_dir, d);
      }
      worst_inv = std::max(worst_inv, std::abs(a.inv_len.to_double() / b.inv_len.to_double() - 1));
    }
  std::printf("raygen vs host rays, 64x48: max |dir difference| %.3g, max inv_len rel. %.3g\n",
              worst_dir, worst_inv);
  EXPECT_LT(worst_dir, 1e-4);  // |d| ~ 1, fp24 ulp 2^-16 ~ 1.5e-5: a few ulps
  EXPECT_LT(worst_inv, 1e-4);
}

}  // namespace
}  // namespace rc::test
