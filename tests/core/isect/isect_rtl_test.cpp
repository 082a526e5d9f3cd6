// The verilated transform unit (rtl/core/rc_xform_unit.sv) and intersection unit
// (rtl/core/rc_isect_unit.sv) against the golden model, bit for bit.
//
// - rc_isect_unit at fp24 against rc::intersect<fp24>() (tb/golden/trace.hpp), for primary and
//   secondary rays' pairs (t_lo = t_eps, the start triangle excluded) and with and without a valid
//   best: hit_o always;
//   t/u/v/dz for accepted hits; and t/u/v/dz whenever the same triangle would be accepted against
//   an empty best (intersect() with best = {+inf, INT32_MAX}), which checks the values of hits
//   that are rejected only by the closest-hit rule.
// - rc_xform_unit at fp24 against ((m0*x + m1*y) + m2*z) [+ m3] written with rc::fp24, for both
//   translate values.
// Both handshakes are exercised with seeded random valid_i gaps and random ready_i low periods
// (some longer than the FIFO, so ready_o drops); every input carries a sequence number as its tag,
// so order, loss and duplication are checked; a stalled output must hold its value. The latency
// and the throughput (one pair every two cycles with the shared transform unit, the default; one
// per cycle with two, SharedXform = 0) are measured against the documented values.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "Visect_e7f16.h"
#include "Visect_e7f16_b.h"
#include "Visect_e7f16_s1.h"
#include "Vxform_e7f16.h"
#include "compiler.hpp"
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
constexpr int kW = T::kWidth;

///////////////////////////////////////////
// A generic valid/ready stream harness  //
///////////////////////////////////////////

// Drv provides: Item, Exp (with a uint32_t tag member), drive(V&, const Item&, uint32_t tag),
// check(const V&, const Exp&) -> error text or "", tag(const V&) -> the output tag.
template <class V, class Drv>
class Stream {
 public:
  using Item = typename Drv::Item;
  using Exp = typename Drv::Exp;

  // gap: 1 in gap_every input slots is idle (0: never); stall: a ready_i low period starts with
  // probability stall_permille/1000 per cycle and lasts 1..max_stall cycles.
  Stream(uint64_t seed, uint32_t gap_every, uint32_t stall_permille, uint32_t max_stall)
      : rng_(seed), gap_every_(gap_every), stall_permille_(stall_permille), max_stall_(max_stall) {
    dut_->valid_i = 0;
    dut_->ready_i = 0;
    dut_.reset(4);
    dut_.tick();
  }

  V& dut() { return dut_.m(); }

  // Offers one item (after a random gap) and holds it until the unit accepts it.
  void push(const Item& it, Exp e) {
    while (gap_every_ != 0 && rng_() % gap_every_ == 0) cycle(false);
    e.tag = next_tag_++;
    Drv::drive(dut_.m(), it, e.tag);
    dut_->valid_i = 1;
    uint64_t waited = 0;
    while (!cycle(true)) ++waited;
    if (waited == 0) ++accepted_at_once_;
    dut_->valid_i = 0;
    exp_.push_back(e);
    ++pushed_;
  }

  // Runs until every expected result came out, then checks that nothing else does.
  void drain() {
    for (int i = 0; i < 100000 && !exp_.empty(); ++i) cycle(false);
    if (!exp_.empty()) fail(std::to_string(exp_.size()) + " results missing after draining");
    for (int i = 0; i < 200; ++i) cycle(false);
  }

  // Cycles from offering one item (ready_i high, empty unit) to valid_o.
  uint64_t measure_latency(const Item& it, Exp e) {
    drain();
    stall_permille_ = 0;
    e.tag = next_tag_++;
    Drv::drive(dut_.m(), it, e.tag);
    dut_->valid_i = 1;
    uint64_t n = 0;
    bool accepted = cycle(true);
    dut_->valid_i = 0;
    if (accepted) exp_.push_back(e), ++pushed_;
    ++n;
    for (; n < 1000; ++n) {
      dut_->ready_i = 0;  // look at valid_o before taking it
      dut_->clk_i = 0;
      dut_->eval();
      if (dut_->valid_o) break;
      cycle(false);
    }
    drain();
    return accepted ? n : 0;
  }

  uint64_t pushed() const { return pushed_; }
  uint64_t mismatches() const { return mismatches_; }
  uint64_t checked_out() const { return checked_out_; }
  uint64_t accepted_at_once() const { return accepted_at_once_; }
  uint64_t cycles() const { return cycles_; }
  uint64_t stalled_cycles() const { return stalled_cycles_; }
  uint64_t not_ready_cycles() const { return not_ready_cycles_; }
  void set_stall(uint32_t permille) { stall_permille_ = permille; }
  void set_gap(uint32_t every) { gap_every_ = every; }

  void fail(const std::string& what) {
    if (++mismatches_ <= 10) ADD_FAILURE() << what;
  }

 private:
  void edge() { dut_.tick(); }

  // One clock cycle; returns whether an offered input was accepted.
  bool cycle(bool offering) {
    if (stall_left_ > 0) {
      --stall_left_;
    } else if (stall_permille_ != 0 && rng_() % 1000 < stall_permille_) {
      stall_left_ = 1 + static_cast<uint32_t>(rng_() % max_stall_);
    }
    dut_->ready_i = stall_left_ == 0;
    dut_->clk_i = 0;
    dut_->eval();
    const bool in_fire = offering && dut_->ready_o;
    if (offering && !dut_->ready_o) ++not_ready_cycles_;
    // A stalled result must still be offered, with the same tag (the RTL asserts full stability).
    if (held_ && (!dut_->valid_o || Drv::tag(dut_.m()) != held_tag_))
      fail("valid_o dropped or changed while stalled (tag " + std::to_string(held_tag_) + ")");
    held_ = dut_->valid_o && !dut_->ready_i;
    if (held_) held_tag_ = Drv::tag(dut_.m()), ++stalled_cycles_;
    if (dut_->valid_o && dut_->ready_i) {
      if (exp_.empty()) {
        fail("valid_o without a pending input (tag " + std::to_string(Drv::tag(dut_.m())) + ")");
      } else {
        const Exp& e = exp_.front();
        if (Drv::tag(dut_.m()) != e.tag) {
          fail("out of order, lost or duplicated: got tag " + std::to_string(Drv::tag(dut_.m())) +
               ", expected " + std::to_string(e.tag));
        } else {
          const std::string err = Drv::check(dut_.m(), e);
          if (!err.empty()) fail("tag " + std::to_string(e.tag) + ": " + err);
        }
        exp_.pop_front();
        ++checked_out_;
      }
    }
    edge();
    ++cycles_;
    return in_fire;
  }

  VerilatedTb<V> dut_;  // fatal on error: a failing RTL assertion ends the test binary
  std::mt19937_64 rng_;
  uint32_t gap_every_, stall_permille_, max_stall_;
  uint32_t stall_left_ = 0;
  std::deque<Exp> exp_;
  uint32_t next_tag_ = 0;
  bool held_ = false;
  uint32_t held_tag_ = 0;
  uint64_t pushed_ = 0, mismatches_ = 0, checked_out_ = 0, accepted_at_once_ = 0, cycles_ = 0;
  uint64_t stalled_cycles_ = 0, not_ready_cycles_ = 0;
};

///////////////////////////////
// The intersection unit     //
///////////////////////////////

struct Case {
  std::array<T, 12> m;
  std::array<T, 3> org, dir;
  int32_t tri = 0;
  T best_t = T::inf();
  int32_t best_tri = -1;
  bool best_valid = true;  // false: no hit yet, whatever best_t and best_tri hold
  bool shadow = false;     // a shadow ray's pair: the hit needs t_eps < t
  bool excl = false;       // the shadow ray's start triangle: never a hit
  // The unit's t_eps_i, a frame's constant, so one value for every case of a stream.
  T t_eps = T::from_double(0.75);
};

struct IsectExp {
  Case c;
  bool hit = false;
  Hit<T> h;  // intersect() against the given best (valid when hit)
  bool vals_known = false;
  Hit<T> vals;  // intersect() against an empty best (valid when vals_known)
  uint32_t tag = 0;
};

IsectExp golden(const Case& c) {
  IsectExp e;
  e.c = c;
  const Ray<T> r{c.org, c.dir, T::from_double(1.0)};
  Hit<T> best;  // {+inf, -1} without a valid best
  best.t = c.best_valid ? c.best_t : T::inf();
  best.tri = c.best_valid ? c.best_tri : -1;
  e.hit = intersect(c.m, r, c.tri, best, e.h, c.shadow ? c.t_eps : T::zero(),
                    c.excl ? &c.tri : nullptr);
  Hit<T> open;
  open.t = T::inf();
  open.tri = std::numeric_limits<int32_t>::max();
  e.vals_known = intersect(c.m, r, c.tri, open, e.vals);
  return e;
}

std::string case_text(const Case& c) {
  std::string s = "m=(";
  for (int k = 0; k < 12; ++k) s += c.m[static_cast<size_t>(k)].hex() + (k < 11 ? "," : ")");
  s += " org=(" + c.org[0].hex() + "," + c.org[1].hex() + "," + c.org[2].hex() + ")";
  s += " dir=(" + c.dir[0].hex() + "," + c.dir[1].hex() + "," + c.dir[2].hex() + ")";
  s += " tri=" + std::to_string(c.tri) + " best=(" + c.best_t.hex() + "," +
       std::to_string(c.best_tri) + (c.best_valid ? ")" : ", not valid)") +
       (c.shadow ? " shadow, t_eps=" + c.t_eps.hex() : "") + (c.excl ? " excluded" : "");
  return s;
}

struct IsectDrv {
  using Item = Case;
  using Exp = IsectExp;
  template <class V>
  static void drive(V& d, const Case& c, uint32_t tag) {
    d.tag_i = tag;
    d.tri_i = static_cast<uint32_t>(c.tri);
    for (int k = 0; k < 12; ++k) put_field(d.m_i, k * kW, kW, c.m[static_cast<size_t>(k)].bits());
    for (int k = 0; k < 3; ++k) {
      put_field(d.org_i, k * kW, kW, c.org[static_cast<size_t>(k)].bits());
      put_field(d.dir_i, k * kW, kW, c.dir[static_cast<size_t>(k)].bits());
    }
    d.best_t_i = c.best_t.bits();
    d.best_tri_i = static_cast<uint32_t>(c.best_tri);
    d.best_valid_i = c.best_valid;
    d.secondary_i = c.shadow;
    d.excl_i = c.excl;
    d.t_eps_i = c.t_eps.bits();
  }
  template <class V>
  static uint32_t tag(const V& d) {
    return d.tag_o;
  }
  template <class V>
  static std::string check(const V& d, const IsectExp& e) {
    std::string err;
    if (d.tri_o != static_cast<uint32_t>(e.c.tri)) err += " tri_o " + std::to_string(d.tri_o);
    if (static_cast<bool>(d.hit_o) != e.hit)
      err += " hit_o " + std::to_string(d.hit_o) + " (golden " + std::to_string(e.hit) + ")";
    const auto vals = [&](const Hit<T>& h, const char* what) {
      if (d.t_o != h.t.bits() || d.u_o != h.u.bits() || d.v_o != h.v.bits() ||
          d.dz_o != h.dz.bits())
        err += std::string(" ") + what + ": rtl t/u/v/dz " + T::from_bits(d.t_o).hex() + "/" +
               T::from_bits(d.u_o).hex() + "/" + T::from_bits(d.v_o).hex() + "/" +
               T::from_bits(d.dz_o).hex() + ", golden " + h.t.hex() + "/" + h.u.hex() + "/" +
               h.v.hex() + "/" + h.dz.hex();
    };
    if (e.hit) vals(e.h, "accepted hit");
    if (e.vals_known) vals(e.vals, "hit against an empty best");
    return err.empty() ? err : err + " | " + case_text(e.c);
  }
};

// Rounds the scene compiler's double transform of triangle (a, b, c); all zeros if degenerate.
std::array<T, 12> tri_matrix(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  std::array<double, 12> md{};
  std::array<T, 12> m;
  const bool ok = scene::unit_triangle_transform(a, b, c, &md);
  for (size_t k = 0; k < 12; ++k) m[k] = ok ? T::from_double(md[k]) : T::zero();
  return m;
}

std::array<T, 3> round3(const glm::dvec3& v) {
  return {T::from_double(v.x), T::from_double(v.y), T::from_double(v.z)};
}

// Random rays against random triangles, a large share aimed at the triangle.
class CaseGen {
 public:
  explicit CaseGen(uint64_t seed) : rng_(seed), specials_(special_values<T>()) {}

  Case next() {
    Case c;
    const glm::dvec3 a{uni(-10, 10), uni(-10, 10), uni(-10, 10)};
    const double s = std::pow(10.0, uni(-2, 1));
    const glm::dvec3 b = a + s * glm::dvec3{uni(-1, 1), uni(-1, 1), uni(-1, 1)};
    glm::dvec3 cc = a + s * glm::dvec3{uni(-1, 1), uni(-1, 1), uni(-1, 1)};
    if (pick(20) == 0) cc = a + uni(-2, 2) * (b - a) + 1e-3 * s * glm::dvec3{uni(-1, 1), 0, 0};
    c.m = tri_matrix(a, b, cc);
    const glm::dvec3 o{uni(-20, 20), uni(-20, 20), uni(-20, 20)};
    double b1 = uni(0, 1), b2 = uni(0, 1);
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const uint32_t kind = pick(100);
    glm::dvec3 d;
    if (kind < 55) {         // inside
    } else if (kind < 70) {  // just outside an edge
      const double eps = std::pow(10.0, uni(-7, -3));
      const uint32_t e = pick(3);
      if (e == 0) b1 = -eps;
      if (e == 1) b2 = -eps;
      if (e == 2) b1 = 1 - b2 + eps;
    } else if (kind < 80) {  // exactly on a vertex or an edge (in double)
      const uint32_t e = pick(6);
      if (e == 0) b1 = 0, b2 = 0;
      if (e == 1) b1 = 1, b2 = 0;
      if (e == 2) b1 = 0, b2 = 1;
      if (e == 3) b1 = 0;
      if (e == 4) b2 = 0;
      if (e == 5) b2 = 1 - b1;
    }
    const glm::dvec3 p = a + b1 * (b - a) + b2 * (cc - a);
    d = (p - o) * std::pow(10.0, uni(-1, 1));
    if (kind >= 80 && kind < 90) d = glm::dvec3{uni(-1, 1), uni(-1, 1), uni(-1, 1)};
    if (kind >= 90 && kind < 94) d = -d;  // the triangle is behind the origin
    c.org = round3(o);
    c.dir = round3(d);
    if (kind >= 94) {  // special values sprinkled over every input
      for (auto& x : c.m)
        if (pick(6) == 0) x = special();
      for (auto& x : c.org)
        if (pick(4) == 0) x = special();
      for (auto& x : c.dir)
        if (pick(4) == 0) x = special();
    }
    c.shadow = pick(3) == 0;
    c.excl = pick(10) == 0;
    c.tri = static_cast<int32_t>(rng_() % 1000000);
    if (pick(50) == 0) c.tri = static_cast<int32_t>(static_cast<uint32_t>(rng_()));
    const uint32_t bk = pick(100);
    if (bk < 50) {
      c.best_t = T::inf();
      c.best_tri = -1;
    } else if (bk < 65) {  // no valid best: the words hold anything, and must not count
      c.best_valid = false;
      c.best_t = pick(2) ? T::from_double(uni(0, 1)) : special();
      c.best_tri = static_cast<int32_t>(static_cast<uint32_t>(rng_()));
    } else if (bk < 85) {  // best = this hit's own t: the index tie break decides
      const IsectExp e = golden(c);
      c.best_t = e.vals_known ? e.vals.t : T::from_double(uni(0, 10));
      const uint32_t w = pick(4);
      const uint32_t ut = static_cast<uint32_t>(c.tri);  // wrapping +-1
      c.best_tri = w == 0   ? -1
                   : w == 1 ? c.tri
                   : w == 2 ? static_cast<int32_t>(ut + 1u)
                            : static_cast<int32_t>(ut - 1u);
      if (pick(10) == 0) c.best_tri = std::numeric_limits<int32_t>::min();
    } else if (bk < 97) {  // a best around this hit's t
      const IsectExp e = golden(c);
      const double t = e.vals_known ? e.vals.t.to_double() : 1.0;
      c.best_t = T::from_double(t * uni(0.5, 1.5));
      c.best_tri = static_cast<int32_t>(rng_() % 1000000);
    } else {
      c.best_t = special();
      c.best_tri = static_cast<int32_t>(static_cast<uint32_t>(rng_()));
    }
    return c;
  }

  uint32_t pick(uint32_t n) { return static_cast<uint32_t>(rng_() % n); }
  double uni(double lo, double hi) {
    return lo + (hi - lo) * std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  }
  T special() { return specials_[rng_() % specials_.size()]; }
  T any() { return T::from_bits(static_cast<uint32_t>(rng_())); }

 private:
  std::mt19937_64 rng_;
  std::vector<T> specials_;
};

// Directed cases: parallel rays, origins in the plane, signed zeros, exact edges and vertices,
// index ties, NaN/inf everywhere, degenerate (all-zero) and non-finite matrices.
std::vector<Case> directed_cases() {
  std::vector<Case> out;
  const auto f = [](double x) { return T::from_double(x); };
  const T ulp = T::from_bits(T::from_double(1.0).bits() + 1) - T::from_double(1.0);
  // The unit triangle (0,0,0), (1,0,0), (0,1,0): its transform is exact, so o' = org.
  const auto unit = tri_matrix({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const auto sv = special_values<T>();
  // Signed zeros, parallel rays (d'z = +-0: t = +-inf or NaN), origins in the plane (o'z = +-0),
  // and every special value as o'z and d'z.
  for (T ox : {f(0.25), T::zero(true), f(1.0), f(0.5)})
    for (T oy : {f(0.25), T::zero(), f(-0.5), f(0.5)})
      for (T oz : sv)
        for (T dz : sv) {
          Case c;
          c.m = unit;
          c.org = {ox, oy, oz};
          c.dir = {T::zero(true), f(0.125), dz};
          c.tri = static_cast<int32_t>(out.size());
          out.push_back(c);
        }
  // Exact edges and vertices: u, v on a grid around 0, 1/2 and 1, including u + v = 1 exactly.
  const std::vector<T> grid = {T::zero(), T::zero(true), T::zero() - ulp, ulp,
                               f(0.25),   f(0.5),        f(0.5) + ulp,    f(0.5) - ulp,
                               f(0.75),   f(1.0) - ulp,  f(1.0),          f(1.0) + ulp};
  for (T x : grid)
    for (T y : grid)
      for (T oz : {f(1.0), f(-1.0), T::zero(), T::zero(true)})
        for (T dz : {f(-1.0), f(1.0), f(-0.5), T::zero(), T::zero(true)}) {
          Case c;
          c.m = unit;
          c.org = {x, y, oz};
          c.dir = {T::zero(), T::zero(true), dz};
          c.tri = 7;
          out.push_back(c);
          // The same hit against best = its own t: lower, equal and higher index, and no best.
          const IsectExp e = golden(c);
          if (e.vals_known)
            for (int32_t bt : {6, 7, 8, -1, std::numeric_limits<int32_t>::max(),
                               std::numeric_limits<int32_t>::min()}) {
              Case d = c;
              d.best_t = e.vals.t;
              d.best_tri = bt;
              out.push_back(d);
              // The same words without a valid best: the hit counts whatever they hold.
              d.best_valid = false;
              out.push_back(d);
            }
        }
  // Hits at u = -0 exactly: o'x = -0 and d'x = -0 (every term of row 0 a signed zero), so the -0
  // that d' keeps by having no translation add shows in u_o. All 128 sign patterns of the zeros.
  for (uint32_t sgn = 0; sgn < 128; ++sgn) {
    const auto z = [&](int bit) { return T::zero((sgn >> bit & 1) != 0); };
    Case c;
    c.m = {f(1.0),    z(0),    z(1),      z(2),      T::zero(), f(1.0),
           T::zero(), f(0.25), T::zero(), T::zero(), f(1.0),    f(-2.0)};
    c.org = {z(3), z(4), f(1.0)};
    c.dir = {z(5), z(6), f(1.0)};
    c.tri = 3;
    out.push_back(c);
  }
  // A shadow ray's hits at t = t_eps and one ulp either side (lt(t_eps, t) decides), with and
  // without the shadow flag and the exclusion.
  {
    const T te = Case{}.t_eps;
    for (T oz : {te, T::from_bits(te.bits() - 1), T::from_bits(te.bits() + 1)})
      for (int k = 0; k < 4; ++k) {
        Case c;
        c.m = unit;
        c.org = {f(0.25), f(0.25), oz};
        c.dir = {T::zero(), T::zero(), f(-1.0)};
        c.tri = 11;
        c.shadow = (k & 1) != 0;
        c.excl = (k & 2) != 0;
        out.push_back(c);
      }
  }
  // Negative triangle indices against the tie break.
  for (int32_t tri : {-5, -1, 0, std::numeric_limits<int32_t>::min()})
    for (int32_t bt : {-6, -5, -1, 0}) {
      Case c;
      c.m = unit;
      c.org = {f(0.25), f(0.25), f(1.0)};
      c.dir = {T::zero(), T::zero(), f(-1.0)};
      c.tri = tri;
      c.best_t = f(1.0);
      c.best_tri = bt;
      out.push_back(c);
    }
  // Degenerate and non-finite matrices, NaN/inf rays and bests.
  CaseGen g(99);
  for (int i = 0; i < 4000; ++i) {
    Case c = g.next();
    const int k = i % 8;
    if (k == 0) c.m.fill(T::zero());
    if (k == 1) c.m.fill(T::zero(true));
    if (k == 2) c.m[static_cast<size_t>(g.pick(12))] = g.pick(2) ? T::nan() : T::inf(g.pick(2));
    if (k == 3) c.org[g.pick(3)] = g.pick(2) ? T::nan() : T::inf(g.pick(2));
    if (k == 4) c.dir[g.pick(3)] = g.pick(2) ? T::nan() : T::inf(g.pick(2));
    if (k == 5) c.best_t = g.pick(2) ? T::nan() : T::inf(g.pick(2));
    if (k == 6) c.dir = {T::zero(g.pick(2)), T::zero(g.pick(2)), T::zero(g.pick(2))};
    if (k == 7)
      for (auto& x : c.m) x = g.any();
    out.push_back(c);
  }
  return out;
}

template <class V>
void run_isect(const std::string& label, uint64_t random_cases, uint64_t seed,
               uint64_t want_latency) {
  Stream<V, IsectDrv> s(seed, 8, 20, 64);
  uint64_t hits = 0, vals = 0, n = 0, ties = 0, tie_hits = 0, closer_only = 0, on_one = 0;
  uint64_t t_nan = 0, t_inf = 0, no_best_hits = 0, below_eps = 0, excluded = 0, shadow_hits = 0;
  const auto push = [&](const Case& c) {
    const IsectExp e = golden(c);
    hits += e.hit;
    vals += e.hit || e.vals_known;
    if (c.best_valid && e.vals_known && eq(e.vals.t, c.best_t)) ++ties, tie_hits += e.hit;
    // Hits whose best words, were they valid, would reject them.
    if (!c.best_valid && e.hit) {
      Case v = c;
      v.best_valid = true;
      no_best_hits += !golden(v).hit;
    }
    // Hits that only t_eps or only the exclusion rejects, and accepted shadow hits.
    if ((c.shadow || c.excl) && !e.hit) {
      Case v = c;
      v.shadow = false;
      v.excl = false;
      if (golden(v).hit) {
        v.shadow = c.shadow;
        below_eps += c.shadow && !golden(v).hit;
        excluded += c.excl;
      }
    }
    shadow_hits += c.shadow && e.hit;
    closer_only += e.vals_known && !e.hit;
    on_one += e.hit && eq(e.h.u + e.h.v, T::from_double(1.0));
    // t itself, for every case (the same expressions as intersect(), for the coverage count only)
    const auto& m = c.m;
    const T oz = ((m[8] * c.org[0] + m[9] * c.org[1]) + m[10] * c.org[2]) + m[11];
    const T dz = (m[8] * c.dir[0] + m[9] * c.dir[1]) + m[10] * c.dir[2];
    const T t = (-oz) / dz;
    t_nan += t.is_nan();
    t_inf += t.is_inf();
    ++n;
    s.push(c, e);
  };
  for (const Case& c : directed_cases()) push(c);
  CaseGen g(seed);
  for (uint64_t i = 0; i < random_cases; ++i) {
    // Alternate stretches with and without stalls and gaps.
    if (i % 200000 == 100000) s.set_stall(0), s.set_gap(0);
    if (i % 200000 == 0) s.set_stall(20), s.set_gap(8);
    push(g.next());
  }
  s.drain();
  report_cases(label.c_str(), n, s.mismatches());
  std::printf(
      "  %llu accepted hits, %llu with t/u/v/dz compared; %llu cycles, %llu output-stall "
      "cycles, %llu cycles with ready_o low while offered\n",
      static_cast<unsigned long long>(hits), static_cast<unsigned long long>(vals),
      static_cast<unsigned long long>(s.cycles()),
      static_cast<unsigned long long>(s.stalled_cycles()),
      static_cast<unsigned long long>(s.not_ready_cycles()));
  std::printf(
      "  coverage: %llu ties t == best.t (%llu accepted by the index), %llu rejected only "
      "as not closer, %llu accepted with u + v == 1, %llu with t NaN, %llu with t inf, %llu "
      "accepted only because best_valid_i = 0, %llu shadow hits accepted, %llu rejected by "
      "t_eps, %llu by the exclusion\n",
      static_cast<unsigned long long>(ties), static_cast<unsigned long long>(tie_hits),
      static_cast<unsigned long long>(closer_only), static_cast<unsigned long long>(on_one),
      static_cast<unsigned long long>(t_nan), static_cast<unsigned long long>(t_inf),
      static_cast<unsigned long long>(no_best_hits), static_cast<unsigned long long>(shadow_hits),
      static_cast<unsigned long long>(below_eps), static_cast<unsigned long long>(excluded));
  EXPECT_EQ(s.mismatches(), 0u);
  EXPECT_EQ(s.checked_out(), n);
  EXPECT_GT(s.not_ready_cycles(), 0u) << "the stalls never filled the credit window";
  EXPECT_GT(ties, 0u);
  EXPECT_GT(tie_hits, 0u);
  EXPECT_GT(on_one, 0u);
  EXPECT_GT(no_best_hits, 0u) << "no case where best_valid_i = 0 had to override the best's words";
  EXPECT_GT(shadow_hits, 0u);
  EXPECT_GT(below_eps, 0u);
  EXPECT_GT(excluded, 0u);

  // Latency: one input into an empty unit, ready_i high.
  Case c = g.next();
  const uint64_t lat = s.measure_latency(c, golden(c));
  std::printf("  latency %llu cycles\n", static_cast<unsigned long long>(lat));
  EXPECT_EQ(lat, want_latency);
  EXPECT_EQ(s.mismatches(), 0u);
}

TEST(IsectRtl, Fp24VsGoldenIntersect) {
  // The contract's latency: issue 2 (input register, second pass), the transform (multiply and
  // three adds), divide, multiply, two adds, compare, the output FIFO.
  constexpr int64_t add = spec::kFpStagesAdd, mul = spec::kFpStagesMul;
  constexpr int64_t lat =
      2 + (mul + 3 * add) + spec::kFpStagesDiv + mul + 2 * add + spec::kFpStagesCmp + 1;
  run_isect<Visect_e7f16>("rtl isect unit (one transform unit) vs golden intersect", 1'000'000, 7,
                          static_cast<uint64_t>(lat));
}

// The same unit with its delay lines in block RAM (BlockDelays = 1, the lit board's): the same
// results at the same latency.
TEST(IsectRtl, Fp24BlockDelaysVsGoldenIntersect) {
  constexpr int64_t add = spec::kFpStagesAdd, mul = spec::kFpStagesMul;
  constexpr int64_t lat =
      2 + (mul + 3 * add) + spec::kFpStagesDiv + mul + 2 * add + spec::kFpStagesCmp + 1;
  run_isect<Visect_e7f16_b>("rtl isect unit (delay lines in block RAM) vs golden intersect",
                            300'000, 17, static_cast<uint64_t>(lat));
}

TEST(IsectRtl, Fp24OneStagePipelines) {
  run_isect<Visect_e7f16_s1>(
      "rtl isect unit (all Stages=1, two transform units) vs golden intersect", 100'000, 8, 10);
}

// Without stalls and gaps, inputs offered back to back: the unit takes one every `every` cycles,
// forever (the n-th input is accepted in cycle every * (n - 1)).
template <class V>
void run_throughput(const char* label, uint64_t every) {
  Stream<V, IsectDrv> s(11, 0, 0, 1);
  CaseGen g(12);
  const uint64_t n = 10000;
  for (uint64_t i = 0; i < n; ++i) {
    const Case c = g.next();
    s.push(c, golden(c));
  }
  const uint64_t cycles = s.cycles();
  s.drain();
  report_cases(label, n, s.mismatches());
  std::printf("  %llu cycles for %llu inputs\n", static_cast<unsigned long long>(cycles),
              static_cast<unsigned long long>(n));
  EXPECT_EQ(cycles, every * (n - 1) + 1);
  EXPECT_EQ(s.not_ready_cycles(), (every - 1) * (n - 1));
  EXPECT_EQ(s.accepted_at_once(), every == 1 ? n : 1);
  EXPECT_EQ(s.mismatches(), 0u);
}

TEST(IsectRtl, Fp24ThroughputOneTransformUnit) {
  run_throughput<Visect_e7f16>("rtl fp24 isect unit (one transform unit), back-to-back inputs", 2);
}

TEST(IsectRtl, Fp24ThroughputBlockDelays) {
  run_throughput<Visect_e7f16_b>(
      "rtl fp24 isect unit (delay lines in block RAM), back-to-back inputs", 2);
}

TEST(IsectRtl, Fp24ThroughputTwoTransformUnits) {
  run_throughput<Visect_e7f16_s1>(
      "rtl fp24 isect unit (two transform units, Stages=1), back-to-back inputs", 1);
}

///////////////////////////////
// The transform unit        //
///////////////////////////////

struct XformItem {
  std::array<T, 12> m;
  std::array<T, 3> v;
  bool translate;
};

struct XformExp {
  XformItem it;
  std::array<T, 3> r;
  uint32_t tag = 0;
};

XformExp xform_golden(const XformItem& it) {
  XformExp e;
  e.it = it;
  const auto& m = it.m;
  const auto& v = it.v;
  for (size_t r = 0; r < 3; ++r) {
    T acc = (m[4 * r] * v[0] + m[4 * r + 1] * v[1]) + m[4 * r + 2] * v[2];
    if (it.translate) acc = acc + m[4 * r + 3];
    e.r[r] = acc;
  }
  return e;
}

struct XformDrv {
  using Item = XformItem;
  using Exp = XformExp;
  template <class V>
  static void drive(V& d, const XformItem& it, uint32_t tag) {
    d.tag_i = tag;
    d.translate_i = it.translate;
    for (int k = 0; k < 12; ++k) put_field(d.m_i, k * kW, kW, it.m[static_cast<size_t>(k)].bits());
    // One copy of the vector per row (the port's contract); every caller passes the same one.
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) {
        put_field(d.v_i, (3 * r + k) * kW, kW, it.v[static_cast<size_t>(k)].bits());
      }
    }
  }
  template <class V>
  static uint32_t tag(const V& d) {
    return d.tag_o;
  }
  template <class V>
  static std::string check(const V& d, const XformExp& e) {
    std::string err;
    for (int r = 0; r < 3; ++r) {
      const auto got = static_cast<uint32_t>(get_field(d.r_o, r * kW, kW));
      if (got != e.r[static_cast<size_t>(r)].bits())
        err += " row " + std::to_string(r) + ": rtl " + T::from_bits(got).hex() + ", model " +
               e.r[static_cast<size_t>(r)].hex();
    }
    if (!err.empty()) {
      err += " | translate=" + std::to_string(e.it.translate) + " m=(";
      for (const T& x : e.it.m) err += x.hex() + " ";
      err += ") v=(" + e.it.v[0].hex() + " " + e.it.v[1].hex() + " " + e.it.v[2].hex() + ")";
    }
    return err;
  }
};

TEST(XformRtl, Fp24VsExpression) {
  Stream<Vxform_e7f16, XformDrv> s(21, 8, 20, 40);
  CaseGen g(22);
  const auto sv = special_values<T>();
  uint64_t n = 0, neg_zero_rows = 0;
  const auto push = [&](const XformItem& it) {
    const XformExp e = xform_golden(it);
    for (const T& x : e.r) neg_zero_rows += x.bits() == T::zero(true).bits();
    s.push(it, e);
    ++n;
  };
  // Signed zeros through both paths: rows summing -0 keep it only without the translation.
  for (T a : {T::zero(), T::zero(true), T::from_double(1.0), T::from_double(-1.0)})
    for (T x : {T::zero(), T::zero(true), T::from_double(2.0)})
      for (T t : {T::zero(), T::zero(true), T::from_double(0.5)})
        for (bool tr : {false, true}) {
          XformItem it;
          it.m = {a, a, a, t, a, -a, a, t, -a, -a, -a, t};
          it.v = {x, -x, x};
          it.translate = tr;
          push(it);
        }
  // Random: values from the scene compiler's transforms, random encodings and special values.
  for (int i = 0; i < 300000; ++i) {
    XformItem it;
    const uint32_t kind = g.pick(4);
    const Case c = g.next();
    it.m = c.m;
    it.v = g.pick(2) ? c.org : c.dir;
    if (kind == 1)
      for (auto& x : it.m) x = g.any();
    if (kind == 2) {
      for (auto& x : it.m) x = sv[g.pick(static_cast<uint32_t>(sv.size()))];
      for (auto& x : it.v) x = sv[g.pick(static_cast<uint32_t>(sv.size()))];
    }
    if (kind == 3)
      for (auto& x : it.v) x = g.any();
    it.translate = g.pick(2) != 0;
    push(it);
  }
  s.drain();
  report_cases("rtl fp24 xform unit vs ((m0*x + m1*y) + m2*z) [+ m3], both translate values", n,
               s.mismatches());
  std::printf("  %llu rows gave -0\n", static_cast<unsigned long long>(neg_zero_rows));
  EXPECT_EQ(s.mismatches(), 0u);
  EXPECT_EQ(s.checked_out(), n);
  EXPECT_GT(neg_zero_rows, 0u);
  EXPECT_GT(s.not_ready_cycles(), 0u);
  XformItem it{};
  it.m.fill(T::from_double(1.0));
  it.v.fill(T::from_double(1.0));
  it.translate = true;
  const uint64_t lat = s.measure_latency(it, xform_golden(it));
  std::printf("  latency %llu cycles\n", static_cast<unsigned long long>(lat));
  // The contract's latency: multiply, three adds, the output FIFO.
  EXPECT_EQ(lat, static_cast<uint64_t>(spec::kFpStagesMul + 3 * spec::kFpStagesAdd + 1));
}

}  // namespace
}  // namespace rc::test
