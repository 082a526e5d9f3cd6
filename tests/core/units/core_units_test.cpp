// The core's datapath units (rtl/core/rc_trav_step.sv, rc_ray_setup.sv, rc_shade_unit.sv,
// rc_fp_to_u8.sv, rc_hit_geom.sv, rc_light_term.sv, rc_hit_light.sv, rc_fp_to_fix.sv,
// rc_fp_to_exp.sv, rc_light_byte.sv, rtl/fp/rc_fp_twice.sv), verilated at fp24, against the golden
// model functions they implement (tb/golden/trace.hpp: trav_step, setup_ray, shade, to_u8,
// hit_geometry, light_sample with ambient_terms, both for a hit and its lights, light_fixed,
// light_exponent, light_byte; fp.hpp's x + x), bit for bit.
//
// The handshake units are driven through their valid/ready ports with seeded random valid_i gaps
// and seeded random ready_i low periods. Every operation carries a sequence number as its tag;
// the harness keeps the expected results in a queue and checks every output against the queue's
// head, so order, loss, duplication and spurious outputs are all caught (a result still missing
// after a long idle time, or an output with nothing pending, is a mismatch).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "Vrc_fp_to_exp.h"
#include "Vrc_fp_to_exp_s2.h"
#include "Vrc_fp_to_fix.h"
#include "Vrc_fp_to_fix_s2.h"
#include "Vrc_fp_to_u8.h"
#include "Vrc_fp_twice.h"
#include "Vrc_hit_geom.h"
#include "Vrc_hit_geom_p12.h"
#include "Vrc_hit_light.h"
#include "Vrc_hit_light_p12.h"
#include "Vrc_light_byte.h"
#include "Vrc_light_term.h"
#include "Vrc_light_term_p12.h"
#include "Vrc_ray_setup.h"
#include "Vrc_shade_unit.h"
#include "Vrc_trav_step.h"
#include "fp.hpp"
#include "fp_cases.hpp"
#include "trace.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::get_field;
using rc::harness::put_field;
using rc::harness::VerilatedTb;
namespace {

using T = fp24;

// The fp units' latencies (docs/spec.toml [fp_stages]); the units' latencies below are the sums
// their contracts state.
constexpr int64_t kAdd = spec::kFpStagesAdd, kMul = spec::kFpStagesMul, kCmp = spec::kFpStagesCmp,
                  kDiv = spec::kFpStagesDiv;
// rc_fp_to_u8: max, min, multiply, round.
constexpr int64_t kToU8Latency = 2 * kCmp + kMul + 1;
// The light units' operations (rc_hit_geom, rc_light_term): every product and sum goes through an
// rc_fp_pool with an input register before its operator (one cycle more than the operator), and
// rc_light_term's fixed-point conversions are rc_fp_to_fix with two stages.
constexpr int64_t kPoolMul = kMul + 1, kPoolAdd = kAdd + 1;
constexpr int64_t kLightFixLatency = 2;
constexpr int kW = T::kWidth;  // 24
constexpr uint32_t kTagMask = 0xffff;

T fb(uint32_t b) { return T::from_bits(b); }

////////////////////////
// Value generators   //
////////////////////////

class Gen {
 public:
  explicit Gen(uint64_t seed) : rng_(seed), specials_(special_values<T>()) {}

  uint32_t u(uint32_t n) { return static_cast<uint32_t>(rng_() % n); }
  bool chance(uint32_t one_in) { return u(one_in) == 0; }
  double unit() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }

  T any() { return fb(static_cast<uint32_t>(rng_())); }
  T special() { return specials_[u(static_cast<uint32_t>(specials_.size()))]; }
  // A normal number with exponent within +-span of 1.0, random sign unless positive.
  T moderate(uint32_t span = 8, bool positive = false) {
    const uint32_t e = T::kBias - span + u(2 * span + 1);
    const uint32_t s = (!positive && (rng_() & 1)) ? T::kSignBit : 0;
    return fb(s | (e << T::kFracW) | (static_cast<uint32_t>(rng_()) & T::kFracMask));
  }
  // x or one of its encoding neighbours (+-1, +-2 in the bit pattern), the other zero, etc.
  T near(T x) {
    switch (u(8)) {
      case 0:
      case 1:
      case 2: return x;
      case 3: return fb((x.bits() + 1) & T::kMask);
      case 4: return fb((x.bits() - 1) & T::kMask);
      case 5: return fb((x.bits() + 2) & T::kMask);
      case 6: return x.is_zero() ? fb(x.bits() ^ T::kSignBit) : fb((x.bits() - 2) & T::kMask);
      default: return x.is_zero() ? fb(x.bits() | (1u + u(T::kFracMask))) : x;  // subnormal enc.
    }
  }
  // A zero: +-0 or a subnormal encoding of either sign.
  T zero_enc() {
    const uint32_t s = (rng_() & 1) ? T::kSignBit : 0;
    return fb(s | (chance(2) ? 0 : 1u + u(T::kFracMask)));
  }

 private:
  std::mt19937_64 rng_;
  std::vector<T> specials_;
};

////////////////////////////////////////
// Handshake harness (valid/ready)    //
////////////////////////////////////////

// An output's ready_i under stalls: low for 1..40 cycles now and then, high otherwise (`low`:
// the cycles of the current low burst still to come).
bool ready_burst(std::mt19937_64& rng, int& low) {
  if (low > 0) {
    --low;
    return false;
  }
  if (rng() % 16 == 0) {
    low = static_cast<int>(rng() % 40);
    return false;
  }
  return true;
}

// Before an input under stalls: now and then (1 in 8) 1..6 idle cycles with valid_i low.
template <class V, class Tick>
void input_gap(std::mt19937_64& rng, V& m, Tick tick) {
  if ((rng() & 7) != 0) return;
  const int gap = 1 + static_cast<int>(rng() % 6);
  m.valid_i = 0;
  for (int i = 0; i < gap; ++i) tick();
}

// Ticks until the presented input is taken (tick() returns whether it was); false when ready_o
// stays low for 100,000 cycles.
template <class Tick>
bool wait_taken(Tick tick) {
  for (uint64_t waited = 0; !tick();)
    if (++waited > 100000) return false;
  return true;
}

// Unit traits: In, Out, drive(V&, In), read(V&) -> Out, golden(In) -> Out, show(In, Out, Out).
template <class V, class U>
class StreamHarness {
 public:
  using In = typename U::In;
  using Out = typename U::Out;

  StreamHarness(uint64_t seed, bool stalls) : rng_(seed), stalls_(stalls) {
    U::init(tb_.m());
    tb_->valid_i = 0;
    tb_->ready_i = 0;
    tb_.reset(4, [this] { tick(); });
    tick();
  }

  // Presents one operation (after a seeded random gap) and holds it until it is taken.
  void push(const In& in) {
    if (stalls_) input_gap(rng_, tb_.m(), [this] { tick(); });
    tb_->valid_i = 1;
    tb_->tag_i = static_cast<uint16_t>(seq_ & kTagMask);
    U::drive(tb_.m(), in);
    q_.push_back({in, U::golden(in), static_cast<uint32_t>(seq_ & kTagMask)});
    ++seq_;
    ++cases_;
    if (!wait_taken([this] { return tick(); })) fail("ready_o stuck low");
    tb_->valid_i = 0;
  }

  // Idles until every result is out (ready_i keeps its random pattern), then some more cycles to
  // catch spurious outputs.
  void drain() {
    tb_->valid_i = 0;
    for (int i = 0; i < 100000 && !q_.empty(); ++i) tick();
    if (!q_.empty()) fail(std::to_string(q_.size()) + " results missing after 100000 idle cycles");
    for (int i = 0; i < 200; ++i) tick();
  }

  // Clock cycle: ready_i pattern, output check and input acceptance (sampled before the edge).
  // Returns whether the presented operation was taken.
  bool tick() {
    tb_->ready_i = next_ready();
    tb_.eval();
    const bool taken = tb_->valid_i && tb_->ready_o;
    if (tb_->valid_o && tb_->ready_i) check_output();
    if (tb_->valid_o && first_out_cycle_ < 0) first_out_cycle_ = static_cast<int64_t>(cycle());
    if (taken && first_take_cycle_ < 0) first_take_cycle_ = static_cast<int64_t>(cycle());
    tb_.tick();
    return taken;
  }

  void set_ready_mode(int mode) { ready_mode_ = mode; }  // 0 random, 1 always, 2 never
  V& dut() { return tb_.m(); }
  uint64_t cases() const { return cases_; }
  uint64_t mismatches() const { return mismatches_; }
  uint64_t cycle() const { return tb_.cycles(); }
  uint64_t outputs() const { return outputs_; }
  int64_t latency() const { return first_out_cycle_ - first_take_cycle_; }
  size_t pending() const { return q_.size(); }

 private:
  struct Expect {
    In in;
    Out want;
    uint32_t tag;
  };

  bool next_ready() {
    if (ready_mode_ == 1) return true;
    if (ready_mode_ == 2) return false;
    return !stalls_ || ready_burst(rng_, ready_low_left_);
  }

  void fail(const std::string& what) {
    if (++mismatches_ <= 10) ADD_FAILURE() << what;
  }

  void check_output() {
    ++outputs_;
    if (q_.empty()) {
      fail("valid_o with nothing pending (spurious or duplicated result), tag " +
           std::to_string(tb_->tag_o));
      return;
    }
    const Expect e = q_.front();
    q_.pop_front();
    const Out got = U::read(tb_.m());
    if (tb_->tag_o != e.tag) {
      fail("tag " + std::to_string(tb_->tag_o) + ", expected " + std::to_string(e.tag) +
           " (order, loss or duplication)");
    } else if (!(got == e.want)) {
      fail(U::show(e.in, got, e.want));
    }
  }

  VerilatedTb<V> tb_;
  std::mt19937_64 rng_;
  bool stalls_;
  std::deque<Expect> q_;
  uint64_t seq_ = 0, cases_ = 0, mismatches_ = 0, outputs_ = 0;
  int64_t first_out_cycle_ = -1, first_take_cycle_ = -1;
  int ready_low_left_ = 0;
  int ready_mode_ = 0;
};

////////////////////////
// rc_trav_step       //
////////////////////////

struct TravUnit {
  struct In {
    T split, org, inv, tmin, tmax;
  };
  struct Out {
    uint32_t t, which;
    bool operator==(const Out& o) const { return t == o.t && which == o.which; }
  };
  static void init(Vrc_trav_step&) {}
  static void drive(Vrc_trav_step& d, const In& in) {
    d.split_i = in.split.bits();
    d.org_i = in.org.bits();
    d.inv_i = in.inv.bits();
    d.tmin_i = in.tmin.bits();
    d.tmax_i = in.tmax.bits();
  }
  static Out read(const Vrc_trav_step& d) { return {d.t_o, d.case_o}; }
  static Out golden(const In& in) {
    const StepResult<T> r = trav_step<T>(in.split, in.org, in.inv, in.tmin, in.tmax);
    return {r.t.bits(), static_cast<uint32_t>(r.which)};
  }
  static std::string show(const In& in, const Out& got, const Out& want) {
    return "trav_step(split " + in.split.hex() + ", org " + in.org.hex() + ", inv " + in.inv.hex() +
           ", tmin " + in.tmin.hex() + ", tmax " + in.tmax.hex() + "): rtl t " + fb(got.t).hex() +
           " case " + std::to_string(got.which) + ", golden t " + fb(want.t).hex() + " case " +
           std::to_string(want.which);
  }
};

TravUnit::In trav_case(Gen& g) {
  TravUnit::In in;
  in.split = g.moderate();
  // Origin: random, exactly on the split plane, or next to it.
  switch (g.u(6)) {
    case 0: in.org = in.split; break;
    case 1: in.org = g.near(in.split); break;
    case 2: in.org = g.any(); break;
    default: in.org = g.moderate(); break;
  }
  // Reciprocal direction: of a random direction, of a zero (+-inf), or anything.
  switch (g.u(8)) {
    case 0: in.inv = T::from_double(1.0) / g.zero_enc(); break;
    case 1: in.inv = g.special(); break;
    case 2: in.inv = g.any(); break;
    default: in.inv = T::from_double(1.0) / g.moderate(); break;
  }
  if (g.chance(16)) in.split = g.special();
  if (g.chance(32)) in.org = g.special();
  const T t = (in.split - in.org) * in.inv;
  // Interval: around t (equal, neighbours, +-0), random, or special.
  const auto pick = [&](bool low) -> T {
    switch (g.u(10)) {
      case 0:
      case 1:
      case 2:
      case 3: return g.near(t);
      case 4: return g.special();
      case 5: return low ? T::zero(g.chance(2)) : T::inf();
      case 6: return g.any();
      default: {
        const T m = g.moderate();
        return low ? (t.is_nan() ? m : min(t, m)) : (t.is_nan() ? m : max(t, m));
      }
    }
  };
  in.tmin = pick(true);
  in.tmax = pick(false);
  if (g.chance(8)) in.tmax = in.tmin;
  return in;
}

////////////////////////
// rc_ray_setup       //
////////////////////////

struct SetupUnit {
  struct In {
    std::array<T, 3> org, dir;
    std::array<T, 6> bounds;
    T tlim = T::inf();  // tmax's limit (a shadow ray's light distance)
  };
  struct Out {
    std::array<uint32_t, 3> inv;
    uint32_t tmin, tmax;
    bool active;
    bool operator==(const Out& o) const {
      return inv == o.inv && tmin == o.tmin && tmax == o.tmax && active == o.active;
    }
  };
  static void init(Vrc_ray_setup&) {}
  static void drive(Vrc_ray_setup& d, const In& in) {
    for (int a = 0; a < 3; ++a) {
      put_field(d.org_i, a * kW, kW, in.org[a].bits());
      put_field(d.dir_i, a * kW, kW, in.dir[a].bits());
    }
    for (int i = 0; i < 6; ++i) put_field(d.bounds_i, i * kW, kW, in.bounds[i].bits());
    d.tlim_i = in.tlim.bits();
  }
  static Out read(const Vrc_ray_setup& d) {
    Out o;
    for (int a = 0; a < 3; ++a) o.inv[a] = static_cast<uint32_t>(get_field(d.inv_o, a * kW, kW));
    o.tmin = d.tmin_o;
    o.tmax = d.tmax_o;
    o.active = d.active_o;
    return o;
  }
  static Out golden(const In& in) {
    Ray<T> r{in.org, in.dir, T::from_double(1.0)};
    const RaySetup<T> s = setup_ray<T>(r, in.bounds, in.tlim);
    return {{s.inv[0].bits(), s.inv[1].bits(), s.inv[2].bits()},
            s.tmin.bits(),
            s.tmax.bits(),
            s.active};
  }
  static std::string show(const In& in, const Out& got, const Out& want) {
    std::ostringstream s;
    s << "setup_ray(org";
    for (T v : in.org) s << ' ' << v.hex();
    s << ", dir";
    for (T v : in.dir) s << ' ' << v.hex();
    s << ", bounds";
    for (T v : in.bounds) s << ' ' << v.hex();
    s << ", tlim " << in.tlim.hex();
    const auto out = [&](const char* who, const Out& o) {
      s << "; " << who << " inv";
      for (uint32_t v : o.inv) s << ' ' << fb(v).hex();
      s << " tmin " << fb(o.tmin).hex() << " tmax " << fb(o.tmax).hex() << " active " << o.active;
    };
    s << ")";
    out("rtl", got);
    out("golden", want);
    return s.str();
  }
};

SetupUnit::In setup_case(Gen& g) {
  SetupUnit::In in;
  const uint32_t box_kind = g.u(16);
  for (int a = 0; a < 3; ++a) {
    T lo = g.moderate(6), hi = lo + g.moderate(6, true);
    if (box_kind == 0) lo = T::inf(true), hi = T::inf();  // unbounded
    if (box_kind == 1 && g.chance(2)) hi = lo;            // flat box
    if (box_kind == 2 && g.chance(2)) std::swap(lo, hi);  // inverted axis
    if (box_kind == 3 && g.chance(3)) (g.chance(2) ? lo : hi) = g.special();
    in.bounds[a] = lo;
    in.bounds[a + 3] = hi;
  }
  const uint32_t org_kind = g.u(8);
  for (int a = 0; a < 3; ++a) {
    const T lo = in.bounds[a], hi = in.bounds[a + 3];
    T o;
    switch (org_kind) {
      case 0: o = g.chance(2) ? lo : hi; break;                  // on a face plane
      case 1: o = g.chance(2) ? g.near(lo) : g.near(hi); break;  // next to it
      case 2: o = g.moderate(8); break;                          // anywhere (outside)
      case 3: o = g.chance(4) ? g.special() : g.moderate(); break;
      default: o = lo + (hi - lo) * T::from_double(g.unit()); break;  // inside
    }
    if (g.chance(6)) o = g.chance(2) ? lo : hi;
    in.org[a] = o;
  }
  const uint32_t dir_kind = g.u(8);
  for (int a = 0; a < 3; ++a) {
    T d = g.moderate(4);
    if (dir_kind < 3 && g.chance(2)) d = g.zero_enc();  // +-0, subnormal encodings
    if (dir_kind == 3 && g.chance(3)) d = g.special();
    if (dir_kind == 4 && g.chance(3)) d = g.any();
    in.dir[a] = d;
  }
  // The limit: +inf (every primary ray) in half the cases; otherwise near the interval's ends,
  // anywhere, or a special value (NaN, zeros, infinities).
  if (g.chance(2)) {
    Ray<T> r{in.org, in.dir, T::from_double(1.0)};
    const RaySetup<T> s = setup_ray<T>(r, in.bounds);
    switch (g.u(6)) {
      case 0: in.tlim = s.tmax; break;
      case 1: in.tlim = g.near(s.tmax); break;
      case 2: in.tlim = g.near(s.tmin); break;
      case 3: in.tlim = s.tmin + (s.tmax - s.tmin) * T::from_double(g.unit()); break;
      case 4: in.tlim = g.special(); break;
      default: in.tlim = g.moderate(6); break;
    }
  }
  return in;
}

////////////////////////
// rc_shade_unit      //
////////////////////////

const T kAmbient = shade_ambient<T>();
const T kDiffuse = shade_diffuse<T>();

struct ShadeUnit {
  struct In {
    T dz, nlen, inv_len;
    std::array<T, 3> kd;
  };
  struct Out {
    std::array<uint32_t, 3> rgb;
    bool operator==(const Out& o) const { return rgb == o.rgb; }
  };
  static void init(Vrc_shade_unit& d) {
    d.ambient_i = kAmbient.bits();
    d.diffuse_i = kDiffuse.bits();
  }
  static void drive(Vrc_shade_unit& d, const In& in) {
    d.dz_i = in.dz.bits();
    d.nlen_i = in.nlen.bits();
    d.inv_len_i = in.inv_len.bits();
    for (int k = 0; k < 3; ++k) put_field(d.kd_i, k * kW, kW, in.kd[k].bits());
  }
  static Out read(const Vrc_shade_unit& d) {
    return {{d.rgb_o & 0xffu, (d.rgb_o >> 8) & 0xffu, (d.rgb_o >> 16) & 0xffu}};
  }
  // shade() itself, on a one-triangle geometry (triangle 0, material 0).
  static Out golden(const In& in) {
    static Geometry<T> geo = [] {
      Geometry<T> g;
      g.normal_len = {T::zero()};
      g.material = {0};
      g.kd = {{T::zero(), T::zero(), T::zero()}};
      return g;
    }();
    geo.normal_len[0] = in.nlen;
    geo.kd[0] = in.kd;
    Ray<T> r{};
    r.inv_len = in.inv_len;
    Hit<T> h;
    h.tri = 0;
    h.dz = in.dz;
    const std::array<uint8_t, 3> b = shade<T>(geo, r, h);
    return {{b[0], b[1], b[2]}};
  }
  static std::string show(const In& in, const Out& got, const Out& want) {
    return "shade(dz " + in.dz.hex() + ", nlen " + in.nlen.hex() + ", inv_len " + in.inv_len.hex() +
           ", kd " + in.kd[0].hex() + " " + in.kd[1].hex() + " " + in.kd[2].hex() + "): rtl " +
           std::to_string(got.rgb[0]) + "," + std::to_string(got.rgb[1]) + "," +
           std::to_string(got.rgb[2]) + ", golden " + std::to_string(want.rgb[0]) + "," +
           std::to_string(want.rgb[1]) + "," + std::to_string(want.rgb[2]);
  }
};

// Whether to_u8(x) meets an exact x.5 tie (the value it rounds, min(max(x, 0), 1) * 255).
bool is_tie(T x) {
  T v = max(x, T::zero());
  if (v.is_nan()) return false;
  v = min(v, T::from_double(1.0)) * T::from_double(255.0);
  const double dv = v.to_double();
  return dv - std::floor(dv) == 0.5;
}

ShadeUnit::In shade_case(Gen& g) {
  ShadeUnit::In in;
  in.dz = g.moderate(6);  // both signs
  in.nlen = g.moderate(6, true);
  const uint32_t c_kind = g.u(8);
  if (c_kind < 4) {
    // c near 1: inv_len ~ 1 / |dz * nlen|, with the encoding nudged around it.
    const T p = (in.dz * in.nlen).abs();
    in.inv_len = g.near(T::from_double(1.0) / p);
  } else if (c_kind < 6) {
    in.inv_len = g.moderate(3, true);
  } else if (c_kind == 6) {
    in.inv_len = g.special();
  } else {
    in.dz = g.chance(2) ? g.special() : g.zero_enc();
    in.inv_len = g.moderate(3, true);
  }
  if (g.chance(32)) in.nlen = g.special();
  // f as the unit will compute it, to aim kd at ties.
  const T c = min(((in.dz * in.nlen) * in.inv_len).abs(), T::from_double(1.0));
  const T f = kAmbient + kDiffuse * c;
  for (int k = 0; k < 3; ++k) {
    switch (g.u(8)) {
      case 0:
      case 1:
      case 2: in.kd[k] = T::from_double(g.unit()); break;                // [0, 1]
      case 3: in.kd[k] = T::from_double(-0.05 + 1.1 * g.unit()); break;  // slightly outside
      case 4: in.kd[k] = g.special(); break;
      default: {
        // kd * f * 255 at or next to n + 0.5
        const double target = (static_cast<double>(g.u(255)) + 0.5) / 255.0;
        const double fd = f.to_double();
        in.kd[k] = g.near(T::from_double(std::isfinite(fd) && fd != 0.0 ? target / fd : target));
        break;
      }
    }
  }
  return in;
}

////////////////////////
// rc_hit_geom        //
////////////////////////

struct HitGeomUnit {
  struct In {
    Ray<T> ray;
    T t, dz;
    std::array<T, 3> n;
    T eta_enter, eta_leave, w, mirror, transmit;
  };
  struct Out {
    bool back = false, mirror = false, refract = false;
    std::array<uint32_t, 3> p{}, n{}, v{}, r{}, refr{};
    uint32_t w_mirror = 0, w_refract = 0;
    bool operator==(const Out& o) const {
      return back == o.back && mirror == o.mirror && refract == o.refract && p == o.p && n == o.n &&
             v == o.v && r == o.r && refr == o.refr && w_mirror == o.w_mirror &&
             w_refract == o.w_refract;
    }
  };
  template <class V>  // rc_hit_geom at either light period
  static void init(V&) {}
  template <class V>  // rc_hit_geom, or rc_hit_light (the same ports for a hit)
  static void drive(V& d, const In& in) {
    for (int a = 0; a < 3; ++a) {
      put_field(d.org_i, a * kW, kW, in.ray.org[a].bits());
      put_field(d.dir_i, a * kW, kW, in.ray.dir[a].bits());
      put_field(d.n_i, a * kW, kW, in.n[a].bits());
    }
    d.inv_len_i = in.ray.inv_len.bits();
    d.t_i = in.t.bits();
    d.dz_i = in.dz.bits();
    d.eta_enter_i = in.eta_enter.bits();
    d.eta_leave_i = in.eta_leave.bits();
    d.w_i = in.w.bits();
    d.mirror_i = in.mirror.bits();
    d.transmit_i = in.transmit.bits();
  }
  template <class V>
  static Out read(const V& d) {
    Out o;
    o.back = d.back_o;
    o.mirror = d.mirror_o;
    o.refract = d.refract_o;
    for (int a = 0; a < 3; ++a) {
      o.p[a] = static_cast<uint32_t>(get_field(d.p_o, a * kW, kW));
      o.n[a] = static_cast<uint32_t>(get_field(d.n_o, a * kW, kW));
      o.v[a] = static_cast<uint32_t>(get_field(d.v_o, a * kW, kW));
      o.r[a] = static_cast<uint32_t>(get_field(d.r_o, a * kW, kW));
      o.refr[a] = static_cast<uint32_t>(get_field(d.refr_o, a * kW, kW));
    }
    o.w_mirror = d.w_mirror_o;
    o.w_refract = d.w_refract_o;
    return o;
  }
  static Out golden(const In& in) {
    const HitGeometry<T> h = hit_geometry(in.ray, in.t, in.dz, in.n, in.eta_enter, in.eta_leave,
                                          in.w, in.mirror, in.transmit);
    Out o;
    o.back = h.back;
    o.mirror = h.mirror;
    o.refract = h.refract;
    for (int a = 0; a < 3; ++a) {
      o.p[a] = h.p[a].bits();
      o.n[a] = h.n[a].bits();
      o.v[a] = h.v[a].bits();
      o.r[a] = h.r[a].bits();
      o.refr[a] = h.t[a].bits();
    }
    o.w_mirror = h.w_mirror.bits();
    o.w_refract = h.w_refract.bits();
    return o;
  }
  static std::string show(const In& in, const Out& got, const Out& want) {
    std::ostringstream s;
    const auto vec = [&](const char* name, const std::array<T, 3>& v) {
      s << " " << name << " " << v[0].hex() << " " << v[1].hex() << " " << v[2].hex();
    };
    s << "hit_geometry(";
    vec("org", in.ray.org);
    vec("dir", in.ray.dir);
    vec("n", in.n);
    s << " inv_len " << in.ray.inv_len.hex() << " t " << in.t.hex() << " dz " << in.dz.hex()
      << " eta " << in.eta_enter.hex() << " " << in.eta_leave.hex() << " w " << in.w.hex()
      << " mirror " << in.mirror.hex() << " transmit " << in.transmit.hex() << "):";
    const auto out = [&](const char* who, const Out& o) {
      s << "\n  " << who << ": back " << o.back << " mirror " << o.mirror << " refract "
        << o.refract << " w " << fb(o.w_mirror).hex() << " " << fb(o.w_refract).hex();
      const std::pair<const char*, const std::array<uint32_t, 3>*> vs[] = {
          {"p", &o.p}, {"n", &o.n}, {"v", &o.v}, {"r", &o.r}, {"refr", &o.refr}};
      for (const auto& [name, v] : vs)
        s << " " << name << " " << fb((*v)[0]).hex() << " " << fb((*v)[1]).hex() << " "
          << fb((*v)[2]).hex();
    };
    out("rtl", got);
    out("golden", want);
    return s.str();
  }
};

// A random unit vector, rounded to the format per component.
std::array<T, 3> unit_vector(Gen& g) {
  double x, y, z, l2;
  do {
    x = 2.0 * g.unit() - 1.0;
    y = 2.0 * g.unit() - 1.0;
    z = 2.0 * g.unit() - 1.0;
    l2 = x * x + y * y + z * z;
  } while (l2 < 1e-6 || l2 > 1.0);
  const double l = std::sqrt(l2);
  return {T::from_double(x / l), T::from_double(y / l), T::from_double(z / l)};
}

// Hits as the core makes them (a unit normal, d'z = d.n for it, inv_len = 1 / |d|, weights and
// factors in [0, 1], ratios of refraction from 1 to 2.5), with the encodings nudged, and now and
// then special values, zeros, weights that underflow or random bit patterns in any field.
HitGeomUnit::In hit_geom_case(Gen& g) {
  HitGeomUnit::In in;
  in.n = unit_vector(g);
  const double scale = std::ldexp(1.0, static_cast<int>(g.u(9)) - 4);
  std::array<T, 3> d = unit_vector(g);
  for (int a = 0; a < 3; ++a) {
    in.ray.org[a] = g.moderate(6);
    in.ray.dir[a] = T::from_double(d[a].to_double() * scale);
  }
  double len2 = 0.0, dn = 0.0;
  for (int a = 0; a < 3; ++a) {
    len2 += in.ray.dir[a].to_double() * in.ray.dir[a].to_double();
    dn += in.ray.dir[a].to_double() * in.n[a].to_double();
  }
  in.ray.inv_len = g.near(T::from_double(1.0 / std::sqrt(len2)));
  in.t = g.moderate(6, true);
  in.dz = g.near(T::from_double(dn));
  const double ior = g.chance(8) ? 1.0 : 1.0 + 1.5 * g.unit();
  in.eta_leave = T::from_double(ior);
  in.eta_enter = T::from_double(1.0 / in.eta_leave.to_double());
  in.w = g.chance(4) ? T::one() : T::from_double(g.unit());
  in.mirror = g.chance(2) ? T::zero() : T::from_double(g.unit());
  in.transmit = g.chance(2) ? T::zero() : T::from_double(g.unit());
  switch (g.u(16)) {
    case 0: in.w = fb(0x010000u | (g.u(1u << 16))); break;  // tiny: w * factor underflows
    case 1: in.mirror = g.special(); break;
    case 2: in.transmit = g.special(); break;
    case 3: in.dz = g.chance(2) ? g.zero_enc() : g.special(); break;
    case 4: in.eta_leave = g.chance(2) ? g.special() : g.moderate(8); break;
    case 5: in.t = g.special(); break;
    case 6: in.n[g.u(3)] = g.special(); break;
    case 7: in.ray.dir[g.u(3)] = g.zero_enc(); break;
    case 8: {  // anything at all
      for (int a = 0; a < 3; ++a) {
        in.ray.org[a] = g.any();
        in.ray.dir[a] = g.any();
        in.n[a] = g.any();
      }
      in.ray.inv_len = g.any();
      in.t = g.any();
      in.dz = g.any();
      in.eta_enter = g.any();
      in.eta_leave = g.any();
      in.w = g.any();
      in.mirror = g.any();
      in.transmit = g.any();
      break;
    }
    default: break;
  }
  return in;
}

////////////////////////
// rc_light_term      //
////////////////////////

constexpr int kFixW = static_cast<int>(spec::kLightFixedBits) + 1;

struct LightTermUnit {
  struct In {
    SurfacePoint<T> sp;
    Geometry<T>::Light light;
    std::array<T, 3> kd, ks;
    uint32_t ns = 0;
    T w;
  };
  struct Out {
    bool present = false;
    std::array<uint32_t, 3> lh{};  // compared when present (the golden model has none else)
    uint32_t t_hi = 0;
    std::array<uint32_t, 3> term{}, amb{};
    bool operator==(const Out& o) const {
      return present == o.present && lh == o.lh && t_hi == o.t_hi && term == o.term && amb == o.amb;
    }
  };
  template <class V>  // rc_light_term at either light period
  static void init(V& d) {
    d.ambient_i = kAmbient.bits();
  }
  template <class V>
  static void drive(V& d, const In& in) {
    for (int a = 0; a < 3; ++a) {
      put_field(d.p_i, a * kW, kW, in.sp.p[a].bits());
      put_field(d.n_i, a * kW, kW, in.sp.n[a].bits());
      put_field(d.v_i, a * kW, kW, in.sp.v[a].bits());
      put_field(d.lpos_i, a * kW, kW, in.light.pos[a].bits());
      put_field(d.lcol_i, a * kW, kW, in.light.color[a].bits());
      put_field(d.kd_i, a * kW, kW, in.kd[a].bits());
      put_field(d.ks_i, a * kW, kW, in.ks[a].bits());
    }
    d.dir_light_i = in.light.directional;
    d.ns_i = static_cast<uint16_t>(in.ns);
    d.w_i = in.w.bits();
  }
  template <class V>
  static Out read(const V& d) {
    Out o;
    o.present = d.present_o;
    o.t_hi = d.t_hi_o;
    for (int a = 0; a < 3; ++a) {
      if (o.present) o.lh[a] = static_cast<uint32_t>(get_field(d.lh_o, a * kW, kW));
      o.term[a] = static_cast<uint32_t>(get_field(d.term_o, a * kFixW, kFixW));
      o.amb[a] = static_cast<uint32_t>(get_field(d.amb_o, a * kFixW, kFixW));
    }
    return o;
  }
  static Out golden(const In& in) {
    const LightSample<T> ls = light_sample(in.sp, in.light, in.kd, in.ks, in.ns, in.w);
    Out o;
    o.present = ls.present;
    o.t_hi = ls.t_hi.bits();
    o.term = ls.term;
    o.amb = ambient_terms(in.kd, in.w);
    if (ls.present)
      for (int a = 0; a < 3; ++a) o.lh[a] = ls.ray.dir[a].bits();
    return o;
  }
  static std::string show(const In& in, const Out& got, const Out& want) {
    std::ostringstream s;
    const auto vec = [&](const char* name, const std::array<T, 3>& v) {
      s << " " << name << " " << v[0].hex() << " " << v[1].hex() << " " << v[2].hex();
    };
    s << "light_sample(";
    vec("p", in.sp.p);
    vec("n", in.sp.n);
    vec("v", in.sp.v);
    s << (in.light.directional ? " directional" : " point");
    vec("pos", in.light.pos);
    vec("colour", in.light.color);
    vec("kd", in.kd);
    vec("ks", in.ks);
    s << " ns " << in.ns << " w " << in.w.hex() << "):";
    const auto out = [&](const char* who, const Out& o) {
      s << "\n  " << who << ": present " << o.present << " t_hi " << fb(o.t_hi).hex() << " lh "
        << fb(o.lh[0]).hex() << " " << fb(o.lh[1]).hex() << " " << fb(o.lh[2]).hex() << " term "
        << o.term[0] << " " << o.term[1] << " " << o.term[2] << " ambient " << o.amb[0] << " "
        << o.amb[1] << " " << o.amb[2];
    };
    out("rtl", got);
    out("golden", want);
    return s.str();
  }
};

// Hits and lights as the lighting makes them: a unit normal facing the view (dot(N, V) < 0 mostly),
// a point light at 0.01 to 100 units or a directional light, colours up to 2, Kd and Ks in [0, 1],
// exponents over the whole range (small ones often); now and then a light at the hit point,
// special values or random bit patterns.
LightTermUnit::In light_term_case(Gen& g) {
  LightTermUnit::In in;
  in.sp.n = unit_vector(g);
  in.sp.v = unit_vector(g);
  if (dot3(in.sp.n, in.sp.v).to_double() > 0.0 && !g.chance(8))
    for (T& x : in.sp.v) x = -x;
  for (T& x : in.sp.p) x = g.moderate(5);
  in.light.directional = g.chance(4);
  const std::array<T, 3> toward = unit_vector(g);
  if (in.light.directional) {
    in.light.pos = toward;
  } else {
    const double dist = std::ldexp(1.0, static_cast<int>(g.u(14)) - 7) * (1.0 + g.unit());
    for (int a = 0; a < 3; ++a)
      in.light.pos[a] = T::from_double(in.sp.p[a].to_double() + dist * toward[a].to_double());
  }
  for (int c = 0; c < 3; ++c) {
    in.light.color[c] = T::from_double(2.0 * g.unit());
    in.kd[c] = T::from_double(g.unit());
    in.ks[c] = g.chance(3) ? T::zero() : T::from_double(g.unit());
  }
  in.ns = g.chance(2) ? g.u(64) : g.u(1u << spec::kLightExponentBits);
  in.w = g.chance(2) ? T::one() : T::from_double(g.unit());
  switch (g.u(24)) {
    case 0: in.light.pos = in.sp.p; break;  // dist2 = 0
    case 1: in.sp.n[g.u(3)] = g.special(); break;
    case 2: in.sp.v[g.u(3)] = g.special(); break;
    case 3: in.light.pos[g.u(3)] = g.special(); break;
    case 4: in.ks[g.u(3)] = g.special(); break;
    case 5: in.w = g.chance(2) ? g.special() : fb(0x010000u | g.u(1u << 16)); break;
    case 6: {  // anything at all
      for (int a = 0; a < 3; ++a) {
        in.sp.p[a] = g.any();
        in.sp.n[a] = g.any();
        in.sp.v[a] = g.any();
        in.light.pos[a] = g.any();
        in.light.color[a] = g.any();
        in.kd[a] = g.any();
        in.ks[a] = g.any();
      }
      in.w = g.any();
      break;
    }
    case 7:  // the half vector's degenerate case: lh = v
      if (in.light.directional) in.light.pos = in.sp.v;
      break;
    default: break;
  }
  return in;
}

/////////////////////////////
// Runners                 //
/////////////////////////////

// cover(in) is called for every case (coverage counters of the caller).
template <class V, class U, class CaseFn, class CoverFn>
void run_random(const char* unit, const char* function, uint64_t n, uint64_t seed, CaseFn make,
                CoverFn cover) {
  StreamHarness<V, U> h(seed, true);
  Gen g(seed * 0x9e3779b97f4a7c15ull + 1);
  for (uint64_t i = 0; i < n; ++i) {
    const typename U::In in = make(g);
    cover(in);
    h.push(in);
  }
  h.drain();
  const std::string what = std::string("rtl ") + unit + " vs golden " + function +
                           " (random, seeded, valid_i gaps and ready_i stalls)";
  report_cases(what.c_str(), h.cases(), h.mismatches());
  EXPECT_EQ(h.mismatches(), 0u);
  EXPECT_EQ(h.outputs(), h.cases());
}

// Latency, full throughput and the credit limit: back to back with ready_i high (an operation
// taken every `interval` cycles: the unit's throughput), then with ready_i low until ready_o
// drops.
template <class V, class U, class CaseFn>
void run_timing(const char* unit, int64_t want_latency, uint64_t want_depth, CaseFn make,
                uint64_t interval = 1, uint64_t phase_wait = 0) {
  StreamHarness<V, U> h(7, false);
  Gen g(8);
  h.set_ready_mode(1);
  const uint64_t n = 1000;
  const uint64_t start = h.cycle();
  // The first push is taken at once (a unit that takes jobs at a fixed phase: within
  // `phase_wait` cycles), each later one `interval` cycles after the one before.
  for (uint64_t i = 0; i < n; ++i) h.push(make(g));
  const uint64_t cycles = h.cycle() - start;
  EXPECT_GE(cycles, (n - 1) * interval + 1) << unit;
  EXPECT_LE(cycles, (n - 1) * interval + 1 + phase_wait)
      << unit << ": not one operation per " << interval << " cycle(s)";
  h.drain();
  EXPECT_EQ(h.latency(), want_latency) << unit << ": latency";
  // ready_i low: the unit must take exactly its FIFO depth of operations, then hold ready_o low.
  // 400 cycles: long enough for a unit at one job per 12 cycles to take 17 (rc_light_term at the
  // lit board's period: 16 intervals and up to 11 cycles for the first phase), then show it
  // stops.
  h.set_ready_mode(2);
  h.dut().valid_i = 1;
  uint64_t taken = 0;
  for (int c = 0; c < 400; ++c) {
    h.dut().tag_i = 0;
    if (h.dut().ready_o) {
      // Present a real operation whenever the unit is ready.
      h.push(make(g));
      ++taken;
    } else {
      h.tick();
    }
  }
  EXPECT_EQ(taken, want_depth) << unit << ": credits";
  h.set_ready_mode(0);
  h.drain();
  EXPECT_EQ(h.mismatches(), 0u);
  EXPECT_EQ(h.pending(), 0u);
  std::printf(
      "[timing] %s: latency %lld cycles, %llu operations taken in %llu cycles, %llu "
      "credits\n",
      unit, static_cast<long long>(h.latency()), static_cast<unsigned long long>(n),
      static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(taken));
}

TEST(CoreUnits, TravStepRandom) {
  std::array<uint64_t, 4> cases{};
  uint64_t t_eq_bound = 0, zero_t = 0;
  run_random<Vrc_trav_step, TravUnit>(
      "rc_trav_step", "trav_step<fp24>", 1'000'000, 101, trav_case, [&](const TravUnit::In& in) {
        const TravUnit::Out o = TravUnit::golden(in);
        ++cases[o.which];
        t_eq_bound += (eq(fb(o.t), in.tmin) || eq(fb(o.t), in.tmax)) ? 1 : 0;
        zero_t += fb(o.t).is_zero() ? 1 : 0;
      });
  std::printf(
      "[info] rc_trav_step coverage: BothWhole %llu, NearOnly %llu, FarOnly %llu, "
      "BothSplit %llu; t equal to tmin or tmax %llu; t = +-0 %llu\n",
      static_cast<unsigned long long>(cases[0]), static_cast<unsigned long long>(cases[1]),
      static_cast<unsigned long long>(cases[2]), static_cast<unsigned long long>(cases[3]),
      static_cast<unsigned long long>(t_eq_bound), static_cast<unsigned long long>(zero_t));
  for (uint64_t c : cases) EXPECT_GT(c, 50'000u);
}

TEST(CoreUnits, TravStepTiming) {
  // Subtract, multiply, compare, the output FIFO; the FIFO holds latency + 1 entries.
  constexpr int64_t lat = kAdd + kMul + kCmp + 1;
  run_timing<Vrc_trav_step, TravUnit>("rc_trav_step", lat, static_cast<uint64_t>(lat + 1),
                                      trav_case);
}

TEST(CoreUnits, RaySetupRandom) {
  uint64_t active = 0, skipped_axes = 0, neg_zero_tmax = 0, zero_dir = 0, clipped = 0,
           limit_off = 0;
  run_random<Vrc_ray_setup, SetupUnit>(
      "rc_ray_setup", "setup_ray<fp24>", 1'000'000, 202, setup_case, [&](const SetupUnit::In& in) {
        const SetupUnit::Out o = SetupUnit::golden(in);
        SetupUnit::In free_in = in;
        free_in.tlim = T::inf();
        const SetupUnit::Out f = SetupUnit::golden(free_in);
        clipped += o.active && o.tmax != f.tmax ? 1 : 0;  // the limit ended an active interval
        limit_off += f.active && !o.active ? 1 : 0;       // the limit made the ray inactive
        active += o.active ? 1 : 0;
        neg_zero_tmax += o.tmax == T::kSignBit ? 1 : 0;
        for (int a = 0; a < 3; ++a) {
          const T inv = fb(o.inv[a]);
          const T t0 = (in.bounds[a] - in.org[a]) * inv, t1 = (in.bounds[a + 3] - in.org[a]) * inv;
          skipped_axes += (t0.is_nan() || t1.is_nan()) ? 1 : 0;
          zero_dir += in.dir[a].is_zero() ? 1 : 0;
        }
      });
  std::printf(
      "[info] rc_ray_setup coverage: active %llu of 1000000; skipped (NaN) axes %llu; "
      "zero direction components %llu; tmax = -0 %llu; tmax ended by the limit %llu, rays made "
      "inactive by it %llu\n",
      static_cast<unsigned long long>(active), static_cast<unsigned long long>(skipped_axes),
      static_cast<unsigned long long>(zero_dir), static_cast<unsigned long long>(neg_zero_tmax),
      static_cast<unsigned long long>(clipped), static_cast<unsigned long long>(limit_off));
  EXPECT_GT(active, 100'000u);
  EXPECT_LT(active, 900'000u);
  EXPECT_GT(skipped_axes, 10'000u);
  EXPECT_GT(clipped, 10'000u);
  EXPECT_GT(limit_off, 10'000u);
}

// rc_ray_setup runs the three axes of a ray through one arithmetic slice: one ray per 3 cycles.
TEST(CoreUnits, RaySetupTiming) {
  // Input register, z two compare gaps after x, divide, multiply, min/max, z's chain step, le,
  // the output FIFO; the FIFO holds latency / (3 x cmp) + 1 entries.
  constexpr int64_t lat = 1 + 2 * kCmp + kDiv + kMul + kCmp + 2 * kCmp + 1;
  run_timing<Vrc_ray_setup, SetupUnit>("rc_ray_setup", lat,
                                       static_cast<uint64_t>(lat / (3 * kCmp) + 1), setup_case, 3);
}

TEST(CoreUnits, ShadeRandom) {
  uint64_t ties = 0;
  run_random<Vrc_shade_unit, ShadeUnit>(
      "rc_shade_unit", "shade<fp24>", 1'000'000, 303, shade_case, [&](const ShadeUnit::In& in) {
        const T c = min(((in.dz * in.nlen) * in.inv_len).abs(), T::from_double(1.0));
        const T f = kAmbient + kDiffuse * c;
        for (T kd : in.kd) ties += is_tie(kd * f) ? 1 : 0;
      });
  std::printf("[info] rc_shade_unit: %llu channels met an exact x.5 tie in to_u8\n",
              static_cast<unsigned long long>(ties));
  EXPECT_GT(ties, 1000u);
}

TEST(CoreUnits, ShadeTiming) {
  // Four multiplies, min, add, to_u8, the output FIFO; the FIFO holds latency + 1 entries.
  constexpr int64_t lat = 4 * kMul + kCmp + kAdd + kToU8Latency + 1;
  run_timing<Vrc_shade_unit, ShadeUnit>("rc_shade_unit", lat, static_cast<uint64_t>(lat + 1),
                                        shade_case);
}

// V: rc_hit_geom at one of the light periods.
template <class V>
void hit_geom_random() {
  uint64_t back = 0, tir = 0, refracted = 0, mirrors = 0, refracts = 0, underflow = 0;
  run_random<V, HitGeomUnit>(
      "rc_hit_geom", "hit_geometry<fp24>", 300'000, 505, hit_geom_case,
      [&](const HitGeomUnit::In& in) {
        const HitGeometry<T> h = hit_geometry(in.ray, in.t, in.dz, in.n, in.eta_enter, in.eta_leave,
                                              in.w, in.mirror, in.transmit);
        back += h.back ? 1 : 0;
        bool same = true;
        for (int a = 0; a < 3; ++a) same = same && h.t[a].bits() == h.r[a].bits();
        tir += same && h.back ? 1 : 0;
        refracted += same ? 0 : 1;
        mirrors += h.mirror ? 1 : 0;
        refracts += h.refract ? 1 : 0;
        underflow += lt(T::zero(), in.w) && lt(T::zero(), in.mirror) && !h.mirror ? 1 : 0;
      });
  std::printf(
      "[info] rc_hit_geom coverage: back %llu of 300000; total internal reflection (leaving) "
      "%llu; refracted %llu; mirror rays %llu, refraction rays %llu; mirror weights that "
      "underflow %llu\n",
      static_cast<unsigned long long>(back), static_cast<unsigned long long>(tir),
      static_cast<unsigned long long>(refracted), static_cast<unsigned long long>(mirrors),
      static_cast<unsigned long long>(refracts), static_cast<unsigned long long>(underflow));
  EXPECT_GT(back, 100'000u);
  EXPECT_GT(tir, 10'000u);
  EXPECT_GT(refracted, 150'000u);
  EXPECT_GT(mirrors, 100'000u);
  EXPECT_GT(refracts, 100'000u);
  EXPECT_GT(underflow, 1'000u);
}

TEST(CoreUnits, HitGeomRandom) { hit_geom_random<Vrc_hit_geom>(); }
TEST(CoreUnits, HitGeomRandomPeriod12) { hit_geom_random<Vrc_hit_geom_p12>(); }

// rc_hit_geom's latency: input register; V, N.V (its products; x + y as y's product leaves, a
// cycle after x's; + z two cycles after x + y leaves), c * c, 1 - c^2, e^2 (1 - c^2), q, sqrt(q),
// g, g * N, e V - g N (products and sums at the pools' latencies); y and z behind x; the output
// FIFO.
constexpr int64_t kHitGeomLatency = 1 + 2 * kPoolMul + 1 + kPoolAdd + 2 + kPoolAdd + 3 * kPoolMul +
                                    4 * kPoolAdd + spec::kFpStagesSqrt + 2 + 1;

// The light units' cycles per job: docs/spec.toml [light] unit_period (the default models), or
// 12 (the _p12 models; the lit board's [board] lit_light_period).
constexpr int64_t kLightPeriod = spec::kLightUnitPeriod;
static_assert(kLightPeriod == 6 || kLightPeriod == 12, "[light] unit_period");
static_assert(spec::kBoardLitLightPeriod == 12, "the _p12 models are the lit board's period");

// rc_hit_geom runs a hit's components through one slice: one hit per unit_period cycles; a hit
// waits at most unit_period - 1 cycles for its phase. The FIFO holds latency / unit_period + 2
// entries.
template <class V>
void hit_geom_timing(int64_t period) {
  constexpr int64_t lat = kHitGeomLatency;
  run_timing<V, HitGeomUnit>("rc_hit_geom", lat, static_cast<uint64_t>(lat / period + 2),
                             hit_geom_case, static_cast<uint64_t>(period),
                             static_cast<uint64_t>(period - 1));
}
TEST(CoreUnits, HitGeomTiming) { hit_geom_timing<Vrc_hit_geom>(kLightPeriod); }
TEST(CoreUnits, HitGeomTimingPeriod12) { hit_geom_timing<Vrc_hit_geom_p12>(12); }

template <class V>
void light_term_random() {
  uint64_t present = 0, directional = 0, spec_on = 0, high_ns = 0, saturated = 0;
  run_random<V, LightTermUnit>("rc_light_term", "light_sample<fp24> and ambient_terms", 200'000,
                               606, light_term_case, [&](const LightTermUnit::In& in) {
                                 const LightSample<T> ls =
                                     light_sample(in.sp, in.light, in.kd, in.ks, in.ns, in.w);
                                 present += ls.present ? 1 : 0;
                                 directional += in.light.directional ? 1 : 0;
                                 for (int c = 0; c < 3; ++c)
                                   saturated += ls.term[c] == kLightOne ? 1 : 0;
                                 spec_on += ls.present && lt(T::zero(), ls.spec) ? 1 : 0;
                                 high_ns += in.ns >= 512 ? 1 : 0;
                               });
  std::printf(
      "[info] rc_light_term coverage: present %llu of 200000, directional lights %llu, a "
      "specular term above 0 %llu, exponents >= 512 %llu, saturated channels %llu\n",
      static_cast<unsigned long long>(present), static_cast<unsigned long long>(directional),
      static_cast<unsigned long long>(spec_on), static_cast<unsigned long long>(high_ns),
      static_cast<unsigned long long>(saturated));
  EXPECT_GT(present, 60'000u);
  EXPECT_LT(present, 160'000u);
  EXPECT_GT(directional, 30'000u);
  EXPECT_GT(spec_on, 20'000u);
  EXPECT_GT(high_ns, 30'000u);
  EXPECT_GT(saturated, 1'000u);
}

TEST(CoreUnits, LightTermRandom) { light_term_random<Vrc_light_term>(); }
TEST(CoreUnits, LightTermRandomPeriod12) { light_term_random<Vrc_light_term_p12>(); }

// rc_light_term's latency: input register; L, L.L (its products, x + y a cycle after x's, + z),
// sqrt, 1 / sqrt, lh, H, H.H (its products, x + y two cycles after x's, + z), sqrt, 1 / sqrt, nh,
// the power (a multiply per bit, b * b as the last one leaves, and the last r * b a cycle after
// its b * b), ks * spec, kd cos + ks spec, * colour, * w, fix (products and sums at the pools'
// latencies); y and z behind x; the output FIFO. H.H enters the shared square root a cycle after
// its sum.
constexpr int64_t kLightTermLatency = 1 + kPoolAdd + kPoolMul + 1 + 2 * kPoolAdd +
                                      spec::kFpStagesSqrt + kDiv + kPoolMul + kPoolAdd + kPoolMul +
                                      2 + 2 * kPoolAdd + 1 + spec::kFpStagesSqrt + kDiv + kPoolMul +
                                      int64_t{spec::kLightExponentBits} * kPoolMul + 1 + kPoolMul +
                                      kPoolAdd + 2 * kPoolMul + kLightFixLatency + 2 + 1;

// rc_light_term takes one job per unit_period cycles; a job waits at most unit_period - 1 cycles
// for its phase.
template <class V>
void light_term_timing(int64_t period) {
  constexpr int64_t lat = kLightTermLatency;
  run_timing<V, LightTermUnit>("rc_light_term", lat, static_cast<uint64_t>(lat / period + 2),
                               light_term_case, static_cast<uint64_t>(period),
                               static_cast<uint64_t>(period - 1));
}
TEST(CoreUnits, LightTermTiming) { light_term_timing<Vrc_light_term>(kLightPeriod); }
TEST(CoreUnits, LightTermTimingPeriod12) { light_term_timing<Vrc_light_term_p12>(12); }

// Inputs x = 0 .. 2^24 - 1 through a valid-only converter (set(model, x) drives its input,
// valid_i -> out, valid_o `latency` cycles later), with seeded random idle cycles (1 in 16): each
// result must come exactly `latency` cycles after its input and equal want(x). Returns the
// mismatches (the first ten are reported as failures).
template <class V, class Set, class Want, class Got>
uint64_t run_every_input(const char* what, uint64_t latency, uint64_t seed, Set set, Want want,
                         Got got) {
  VerilatedTb<V> tb;
  std::mt19937_64 rng(seed);
  tb->valid_i = 0;
  tb.reset(2);
  tb.tick();
  struct Expect {
    uint32_t x;
    uint32_t want;
    uint64_t due;
  };
  std::deque<Expect> q;
  uint64_t cases = 0, mismatches = 0;
  const auto fail = [&](const std::string& m) {
    if (++mismatches <= 10) ADD_FAILURE() << what << ": " << m;
  };
  const auto check = [&] {
    tb.eval();
    if (!tb->valid_o) return;
    if (q.empty()) return fail("valid_o with nothing pending");
    const Expect e = q.front();
    q.pop_front();
    if (e.due != tb.cycles())
      fail("latency: the result of " + fb(e.x).hex() + " not " + std::to_string(latency) +
           " cycles late");
    const uint32_t out = got(tb.m());
    if (out != e.want)
      fail("x = " + fb(e.x).hex() + ": rtl " + std::to_string(out) + ", golden " +
           std::to_string(e.want));
  };
  for (uint32_t x = 0; x <= T::kMask;) {
    const bool idle = (rng() & 15) == 0;
    tb->valid_i = !idle;
    set(tb.m(), x);
    if (!idle) {
      q.push_back({x, want(x), tb.cycles() + latency});
      ++cases;
      ++x;
    }
    check();
    tb.tick();
  }
  tb->valid_i = 0;
  for (uint64_t i = 0; i < latency + 20; ++i) {
    check();
    tb.tick();
  }
  if (!q.empty()) fail(std::to_string(q.size()) + " results missing");
  report_cases((std::string("rtl ") + what).c_str(), cases, mismatches);
  EXPECT_EQ(cases, uint64_t{T::kMask} + 1);
  return mismatches;
}

// Every fp24 encoding x through a converter whose input is x_i (run_every_input).
template <class V, class Want, class Got>
uint64_t run_every_encoding(const char* what, uint64_t latency, uint64_t seed, Want want, Got got) {
  return run_every_input<V>((std::string(what) + ": every fp24 encoding").c_str(), latency, seed,
                            [](V& m, uint32_t x) { m.x_i = x; }, want, got);
}

// rc_fp_to_fix (valid-only, latency 1) against light_fixed<fp24>() for every fp24 encoding.
TEST(CoreUnits, ToFixExhaustive) {
  const uint64_t bad = run_every_encoding<Vrc_fp_to_fix>(
      "rc_fp_to_fix vs golden light_fixed<fp24>", 1, 505,
      [](uint32_t x) { return light_fixed<T>(fb(x)); },
      [](const Vrc_fp_to_fix& m) { return static_cast<uint32_t>(m.out_o); });
  EXPECT_EQ(bad, 0u);
  // The inputs cover the rounding's ties: encodings whose value x 2^fixed_bits is an exact x.5.
  uint64_t ties = 0;
  for (uint32_t x = 0; x <= T::kMask; ++x) {
    const double v = fb(x).to_double() * kLightOne;
    ties += v > 0.0 && v < kLightOne && v - std::floor(v) == 0.5 ? 1 : 0;
  }
  std::printf("[info] rc_fp_to_fix: %llu encodings at an exact x.5 tie\n",
              static_cast<unsigned long long>(ties));
  EXPECT_GT(ties, 1000u);
}

// rc_fp_to_fix with Stages = 2 (rc_light_term's: latency 2) against light_fixed<fp24>() for every
// fp24 encoding.
TEST(CoreUnits, ToFixTwoStagesExhaustive) {
  const uint64_t bad = run_every_encoding<Vrc_fp_to_fix_s2>(
      "rc_fp_to_fix (Stages 2) vs golden light_fixed<fp24>", kLightFixLatency, 506,
      [](uint32_t x) { return light_fixed<T>(fb(x)); },
      [](const Vrc_fp_to_fix_s2& m) { return static_cast<uint32_t>(m.out_o); });
  EXPECT_EQ(bad, 0u);
}

// rc_fp_to_exp (rc_fp_to_fix with no fraction bits and a clamp that is not a power of two,
// valid-only, latency 1) against light_exponent<fp24>() for every fp24 encoding.
TEST(CoreUnits, ToExpExhaustive) {
  const uint64_t bad = run_every_encoding<Vrc_fp_to_exp>(
      "rc_fp_to_exp vs golden light_exponent<fp24>", 1, 606,
      [](uint32_t x) { return light_exponent<T>(fb(x)); },
      [](const Vrc_fp_to_exp& m) { return static_cast<uint32_t>(m.ns_o); });
  EXPECT_EQ(bad, 0u);
  // The inputs cover the rounding's ties (x.5 below the clamp) and the values just below the
  // clamp that round up to 2^exponent_bits.
  uint64_t ties = 0, near_top = 0;
  for (uint32_t x = 0; x <= T::kMask; ++x) {
    const double v = fb(x).to_double();
    ties += v > 0.0 && v < kLightExponentMax && v - std::floor(v) == 0.5 ? 1 : 0;
    near_top += v >= kLightExponentMax + 0.5 && v < kLightExponentMax + 1.0 ? 1 : 0;
  }
  std::printf("[info] rc_fp_to_exp: %llu encodings at an exact x.5 tie, %llu in [1023.5, 1024)\n",
              static_cast<unsigned long long>(ties), static_cast<unsigned long long>(near_top));
  EXPECT_GT(ties, 1000u);
  EXPECT_GT(near_top, 10u);
}

// rc_fp_to_exp with Stages = 2 (rc_tracer's: latency 2) against light_exponent<fp24>() for every
// fp24 encoding (the same inputs as above: ties and values just below the clamp).
TEST(CoreUnits, ToExpTwoStagesExhaustive) {
  const uint64_t bad = run_every_encoding<Vrc_fp_to_exp_s2>(
      "rc_fp_to_exp (Stages 2) vs golden light_exponent<fp24>", 2, 607,
      [](uint32_t x) { return light_exponent<T>(fb(x)); },
      [](const Vrc_fp_to_exp_s2& m) { return static_cast<uint32_t>(m.ns_o); });
  EXPECT_EQ(bad, 0u);
}

// rc_light_byte (valid-only, latency 2) against light_byte(): every sum below 2^23 (2^16 and up
// clamp) and 2^23 sums spread over the whole 32-bit range (x scrambled by an odd multiplier).
TEST(CoreUnits, LightByteEverySum) {
  const auto sum = [](uint32_t x) { return x < (1u << 23) ? x : x * 0x9E3779B1u; };
  const uint64_t bad = run_every_input<Vrc_light_byte>(
      "rc_light_byte vs golden light_byte: sums 0 .. 2^23 - 1 and 2^23 over 32 bits", 2, 707,
      [&](Vrc_light_byte& m, uint32_t x) { m.sum_i = sum(x); },
      [&](uint32_t x) { return static_cast<uint32_t>(light_byte(sum(x))); },
      [](const Vrc_light_byte& m) { return static_cast<uint32_t>(m.byte_o); });
  EXPECT_EQ(bad, 0u);
}

// rc_fp_twice (valid-only, latency 1: rc_hit_geom's c + c) against the golden x + x for every
// fp24 encoding.
TEST(CoreUnits, TwiceExhaustive) {
  const uint64_t bad = run_every_encoding<Vrc_fp_twice>(
      "rc_fp_twice vs golden x + x", 1, 808, [](uint32_t x) { return (fb(x) + fb(x)).bits(); },
      [](const Vrc_fp_twice& m) { return static_cast<uint32_t>(m.res_o); });
  EXPECT_EQ(bad, 0u);
}

// rc_fp_to_u8 (valid-only, latency kToU8Latency) against to_u8<fp24>() for every fp24 encoding.
TEST(CoreUnits, ToU8Exhaustive) {
  const uint64_t bad = run_every_encoding<Vrc_fp_to_u8>(
      "rc_fp_to_u8 vs golden to_u8<fp24>", kToU8Latency, 404,
      [](uint32_t x) { return static_cast<uint32_t>(to_u8<T>(fb(x))); },
      [](const Vrc_fp_to_u8& m) { return static_cast<uint32_t>(m.byte_o); });
  EXPECT_EQ(bad, 0u);
}

////////////////////////
// rc_hit_light       //
////////////////////////

constexpr int kMaxLights = static_cast<int>(spec::kLightMaxLights);

// A hit and its material as the lighting takes them, and the lights of its configuration.
struct HitLightCase {
  HitGeomUnit::In hit;
  std::array<T, 3> kd, ks;
  uint32_t ns = 0;
};
using LightSet = std::array<Geometry<T>::Light, kMaxLights>;

// What rc_hit_light's two outputs give for one hit.
struct HitLightGeo {
  std::array<uint32_t, 3> p{}, r{}, refr{};
  uint32_t w_mirror = 0, w_refract = 0;
  bool mirror = false, refract = false;
  bool operator==(const HitLightGeo& o) const {
    return p == o.p && r == o.r && refr == o.refr && w_mirror == o.w_mirror &&
           w_refract == o.w_refract && mirror == o.mirror && refract == o.refract;
  }
};
struct HitLightSample {
  uint32_t light = 0;
  bool lane_last = false, light_last = false;
  std::array<uint32_t, 3> org{};
  LightTermUnit::Out s;
  bool operator==(const HitLightSample& o) const {
    return light == o.light && lane_last == o.lane_last && light_last == o.light_last &&
           org == o.org && s == o.s;
  }
};

// The bench: packets of hits through valid_i/ready_o with seeded random gaps, geo_ready_i and
// lt_ready_i each with seeded random low bursts of their own; every output checked against the
// head of its queue of golden results (hit_geometry per hit; light_sample and ambient_terms per
// light and hit).
// M: rc_hit_light at one of the light periods.
template <class M>
class HitLightBench {
 public:
  HitLightBench(uint64_t seed, bool stalls) : rng_(seed), stalls_(stalls) {
    tb_->ambient_i = kAmbient.bits();
    tb_->valid_i = 0;
    tb_->geo_ready_i = 0;
    tb_->lt_ready_i = 0;
    tb_.reset(4, [this] { tick(); });
    tick();
  }

  // Sets the configuration (lights 0 .. count - 1 of `lights`); only while the unit is empty.
  void configure(const LightSet& lights, uint32_t count) {
    count_ = count;
    lights_ = lights;
    tb_->light_count_i = static_cast<uint8_t>(count);
    tb_->light_dir_i = 0;
    for (int l = 0; l < kMaxLights; ++l) {
      tb_->light_dir_i |= static_cast<uint8_t>((lights[l].directional ? 1u : 0u) << l);
      for (int a = 0; a < 3; ++a) {
        put_field(tb_->light_pos_i, (3 * l + a) * kW, kW, lights[l].pos[a].bits());
        put_field(tb_->light_col_i, (3 * l + a) * kW, kW, lights[l].color[a].bits());
      }
    }
  }

  // Presents a packet's hits one after the other (each after a seeded random gap), last_i on
  // the last.
  void push(const std::vector<HitLightCase>& packet) {
    std::vector<uint32_t> tags;
    for (size_t k = 0; k < packet.size(); ++k) {
      const HitLightCase& c = packet[k];
      if (stalls_) input_gap(rng_, tb_.m(), [this] { tick(); });
      const uint32_t tag = static_cast<uint32_t>(seq_++ & kTagMask);
      tags.push_back(tag);
      tb_->valid_i = 1;
      tb_->tag_i = static_cast<uint16_t>(tag);
      tb_->last_i = k + 1 == packet.size();
      M& d = tb_.m();
      HitGeomUnit::drive(d, c.hit);  // the same port names as rc_hit_geom's
      for (int a = 0; a < 3; ++a) {
        put_field(d.kd_i, a * kW, kW, c.kd[a].bits());
        put_field(d.ks_i, a * kW, kW, c.ks[a].bits());
      }
      d.ns_i = static_cast<uint16_t>(c.ns);
      ++hits_;
      if (!wait_taken([this] { return tick(); })) fail("ready_o stuck low");
      tb_->valid_i = 0;
      // The hit's geometry may leave before the packet's later hits are taken (input gaps).
      const HitGeomUnit::Out h = HitGeomUnit::golden(c.hit);
      geo_q_.push_back({tag, {h.p, h.r, h.refr, h.w_mirror, h.w_refract, h.mirror, h.refract}});
    }
    expect(packet, tags);
  }

  // Idles until both queues are empty, then some more cycles to catch spurious outputs.
  void drain() {
    tb_->valid_i = 0;
    for (int i = 0; i < 100000 && (!geo_q_.empty() || !lt_q_.empty()); ++i) tick();
    if (!geo_q_.empty() || !lt_q_.empty())
      fail(std::to_string(geo_q_.size()) + " geo and " + std::to_string(lt_q_.size()) +
           " light results missing after 100000 idle cycles");
    for (int i = 0; i < 300; ++i) tick();
  }

  bool tick() {
    tb_->geo_ready_i = ready(geo_low_);
    tb_->lt_ready_i = ready(lt_low_);
    tb_.eval();
    const bool taken = tb_->valid_i && tb_->ready_o;
    if (taken && first_take_ < 0) first_take_ = static_cast<int64_t>(cycle());
    if (tb_->geo_valid_o && first_geo_ < 0) first_geo_ = static_cast<int64_t>(cycle());
    if (tb_->lt_valid_o && first_lt_ < 0) first_lt_ = static_cast<int64_t>(cycle());
    if (tb_->geo_valid_o && tb_->geo_ready_i) check_geo();
    if (tb_->lt_valid_o && tb_->lt_ready_i) check_lt();
    tb_.tick();
    return taken;
  }

  // Cycles from the first hit's take to the first geo and the first light output.
  int64_t geo_latency() const { return first_geo_ - first_take_; }
  int64_t lt_latency() const { return first_lt_ - first_take_; }

  uint64_t hits() const { return hits_; }
  uint64_t samples() const { return samples_; }
  uint64_t mismatches() const { return mismatches_; }
  uint64_t cycle() const { return tb_.cycles(); }
  bool ready_o() { return tb_->ready_o; }

 private:
  template <class Out>
  struct Expect {
    uint32_t tag;
    Out want;
  };

  // The golden light samples of a packet, per light each hit's (its geometry is expected as each
  // hit is taken, in push()).
  void expect(const std::vector<HitLightCase>& packet, const std::vector<uint32_t>& tags) {
    std::vector<HitGeomUnit::Out> hg;
    for (size_t k = 0; k < packet.size(); ++k) {
      hg.push_back(HitGeomUnit::golden(packet[k].hit));
    }
    for (uint32_t l = 0; l < count_; ++l)
      for (size_t k = 0; k < packet.size(); ++k) {
        const HitLightCase& c = packet[k];
        HitLightSample s;
        s.light = l;
        s.lane_last = k + 1 == packet.size();
        s.light_last = l + 1 == count_;
        s.org = hg[k].p;
        LightTermUnit::In li;
        for (int a = 0; a < 3; ++a) {
          li.sp.p[a] = fb(hg[k].p[a]);
          li.sp.n[a] = fb(hg[k].n[a]);
          li.sp.v[a] = fb(hg[k].v[a]);
        }
        li.light = lights_[l];
        li.kd = c.kd;
        li.ks = c.ks;
        li.ns = c.ns;
        li.w = c.hit.w;
        s.s = LightTermUnit::golden(li);
        lt_q_.push_back({tags[k], s});
      }
  }

  bool ready(int& low) { return !stalls_ || ready_burst(rng_, low); }

  void fail(const std::string& what) {
    if (++mismatches_ <= 10) ADD_FAILURE() << what;
  }

  void check_geo() {
    const M& d = tb_.m();
    if (geo_q_.empty())
      return fail("geo_valid_o with nothing pending, tag " + std::to_string(d.geo_tag_o));
    const Expect<HitLightGeo> e = geo_q_.front();
    geo_q_.pop_front();
    HitLightGeo g;
    for (int a = 0; a < 3; ++a) {
      g.p[a] = static_cast<uint32_t>(get_field(d.geo_p_o, a * kW, kW));
      g.r[a] = static_cast<uint32_t>(get_field(d.geo_r_o, a * kW, kW));
      g.refr[a] = static_cast<uint32_t>(get_field(d.geo_refr_o, a * kW, kW));
    }
    g.w_mirror = d.geo_w_mirror_o;
    g.w_refract = d.geo_w_refract_o;
    g.mirror = d.geo_mirror_o;
    g.refract = d.geo_refract_o;
    if (d.geo_tag_o != e.tag)
      fail("geo tag " + std::to_string(d.geo_tag_o) + ", expected " + std::to_string(e.tag));
    else if (!(g == e.want))
      fail("geo of hit " + std::to_string(e.tag) + " differs from hit_geometry()");
  }

  void check_lt() {
    const M& d = tb_.m();
    ++samples_;
    if (lt_q_.empty())
      return fail("lt_valid_o with nothing pending, tag " + std::to_string(d.lt_tag_o));
    const Expect<HitLightSample> e = lt_q_.front();
    lt_q_.pop_front();
    HitLightSample s;
    s.light = d.lt_light_o;
    s.lane_last = d.lt_lane_last_o;
    s.light_last = d.lt_light_last_o;
    s.s.present = d.lt_present_o;
    s.s.t_hi = d.lt_t_hi_o;
    for (int a = 0; a < 3; ++a) {
      s.org[a] = static_cast<uint32_t>(get_field(d.lt_org_o, a * kW, kW));
      if (s.s.present) s.s.lh[a] = static_cast<uint32_t>(get_field(d.lt_dir_o, a * kW, kW));
      s.s.term[a] = static_cast<uint32_t>(get_field(d.lt_term_o, a * kFixW, kFixW));
      s.s.amb[a] = static_cast<uint32_t>(get_field(d.lt_amb_o, a * kFixW, kFixW));
    }
    if (d.lt_tag_o != e.tag)
      fail("light tag " + std::to_string(d.lt_tag_o) + ", expected " + std::to_string(e.tag));
    else if (!(s == e.want))
      fail("light " + std::to_string(e.want.light) + " of hit " + std::to_string(e.tag) +
           ": rtl light " + std::to_string(s.light) + " last " + std::to_string(s.lane_last) +
           std::to_string(s.light_last) + " present " + std::to_string(s.s.present) +
           ", golden present " + std::to_string(e.want.s.present) +
           (s.org == e.want.org ? "" : "; origins differ"));
  }

  VerilatedTb<M> tb_;
  std::mt19937_64 rng_;
  bool stalls_;
  LightSet lights_{};
  uint32_t count_ = 0;
  std::deque<Expect<HitLightGeo>> geo_q_;
  std::deque<Expect<HitLightSample>> lt_q_;
  uint64_t seq_ = 0, hits_ = 0, samples_ = 0, mismatches_ = 0;
  int64_t first_take_ = -1, first_geo_ = -1, first_lt_ = -1;
  int geo_low_ = 0, lt_low_ = 0;
};

HitLightCase hit_light_case(Gen& g) {
  HitLightCase c;
  c.hit = hit_geom_case(g);
  const LightTermUnit::In m = light_term_case(g);  // its material
  c.kd = m.kd;
  c.ks = m.ks;
  c.ns = m.ns;
  return c;
}

// A configuration's lights: as light_term_case() makes them, around the origin.
LightSet light_set(Gen& g) {
  LightSet s;
  for (Geometry<T>::Light& l : s) l = light_term_case(g).light;
  return s;
}

// A packet of 1 to 4 hits.
std::vector<HitLightCase> hit_light_packet(Gen& g) {
  std::vector<HitLightCase> p(1 + g.u(4));
  for (HitLightCase& c : p) c = hit_light_case(g);
  return p;
}

// Every light count 0 .. MaxLights (each with lights of its own) under random stalls on the input
// and on both outputs: each hit's geometry and its light samples, in order, bit for bit.
template <class M>
void hit_light_random() {
  Gen g(707);
  HitLightBench<M> b(708, true);
  uint64_t samples = 0;
  for (const uint32_t count : {1u, 2u, 4u, 0u, 3u, 1u}) {
    b.configure(light_set(g), count);
    const uint64_t before = b.hits();
    while (b.hits() - before < 8000) b.push(hit_light_packet(g));
    samples += (b.hits() - before) * count;
    b.drain();
    EXPECT_EQ(b.mismatches(), 0u) << count << " lights";
  }
  report_cases("rtl rc_hit_light vs hit_geometry, light_sample and ambient_terms", b.hits(),
               b.mismatches());
  std::printf("[info] rc_hit_light: %llu hits, %llu light samples, %llu cycles\n",
              static_cast<unsigned long long>(b.hits()),
              static_cast<unsigned long long>(b.samples()),
              static_cast<unsigned long long>(b.cycle()));
  EXPECT_EQ(b.samples(), samples);
}

TEST(CoreUnits, HitLightRandom) { hit_light_random<Vrc_hit_light>(); }
TEST(CoreUnits, HitLightRandomPeriod12) { hit_light_random<Vrc_hit_light_p12>(); }

// Without stalls, packets of four hits: a hit per unit_period cycles with at most one light and
// one per unit_period x count cycles with more: N hits take at most that many cycles plus the
// pipeline's fill and drain.
template <class M>
void hit_light_throughput(int64_t period) {
  Gen g(709);
  for (const uint32_t count : {0u, 1u, 2u, 4u}) {
    HitLightBench<M> b(710, false);
    b.configure(light_set(g), count);
    constexpr uint64_t kHits = 2000;  // packets of 4
    const uint64_t start = b.cycle();
    for (uint64_t i = 0; i < kHits / 4; ++i) {
      std::vector<HitLightCase> p(4);
      for (HitLightCase& c : p) c = hit_light_case(g);
      b.push(p);
    }
    const uint64_t cycles = b.cycle() - start;
    b.drain();
    EXPECT_EQ(b.mismatches(), 0u);
    const uint64_t per = static_cast<uint64_t>(period) * std::max(count, 1u);
    std::printf(
        "[timing] rc_hit_light (period %lld), %u lights: %llu hits taken in %llu cycles "
        "(%.3f per hit); latency %lld cycles to the geometry, %s to the first light\n",
        static_cast<long long>(period), count, static_cast<unsigned long long>(kHits),
        static_cast<unsigned long long>(cycles),
        static_cast<double>(cycles) / static_cast<double>(kHits),
        static_cast<long long>(b.geo_latency()),
        count > 0 ? std::to_string(b.lt_latency()).c_str() : "none");
    // The geometry: rc_hit_geom's latency and the geo FIFO's head register. The first light
    // sample: the packet's fourth hit is taken 3 x unit_period cycles after its first, its
    // geometry enters the lane memory, whose bank is issued from the cycle after; the job waits
    // at most unit_period - 1 cycles for its phase, then rc_light_term's latency.
    EXPECT_EQ(b.geo_latency(), kHitGeomLatency + 1);
    if (count > 0) {
      EXPECT_GE(b.lt_latency(), kHitGeomLatency + 3 * period + 1 + kLightTermLatency);
      EXPECT_LE(b.lt_latency(), kHitGeomLatency + 3 * period + 1 + period - 1 + kLightTermLatency);
    }
    EXPECT_LE(cycles, per * kHits + 8) << count << " lights";
  }
}

TEST(CoreUnits, HitLightThroughput) { hit_light_throughput<Vrc_hit_light>(kLightPeriod); }
TEST(CoreUnits, HitLightThroughputPeriod12) { hit_light_throughput<Vrc_hit_light_p12>(12); }

}  // namespace
}  // namespace rc::test
