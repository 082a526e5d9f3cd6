// The golden model of the ray tracing core: packet kd-tree traversal, list walking, intersection
// through the unit-triangle transform, closest hit, shading. Every rule here is specified in
// docs/architecture.md ("The core's rules"); the RTL implements exactly these rules, so every
// arithmetic operation is a format operation (rc::Fp) in the order written.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "fp.hpp"
#include "rc_constants.hpp"

namespace rc {

constexpr int kPacketRays = 4;

// Error bits, as the hardware reports them (docs/architecture.md, "Errors"; bit numbers from
// docs/spec.toml [core_status], which rc_core's error_o uses too).
enum ErrorBits : uint32_t {
  kErrNone = 0,
  // inner node with its children out of range, or NaN/inf split
  kErrMalformedNode = 1u << spec::kCoreStatusMalformedNode,
  // leaf list range or triangle index outside the image
  kErrBadAddress = 1u << spec::kCoreStatusBadAddress,
  // a push with StackDepth entries on the stack
  kErrStackOverflow = 1u << spec::kCoreStatusStackOverflow,
};

// A decoded kd node (docs/memory-format.md, "kd nodes").
struct Node {
  uint32_t kind;   // 0, 1, 2: inner node splitting x, y, z; 3: leaf
  uint32_t index;  // inner: left child (right = left + 1); leaf: first list entry
  uint32_t upper;  // inner: split value bits; leaf: triangle count
};

inline Node decode_node(uint64_t w) {
  return {static_cast<uint32_t>(w & 3u), static_cast<uint32_t>((w >> 2) & 0x3fffffffu),
          static_cast<uint32_t>(w >> 32)};
}

// Geometry as the core sees it: the memory image's sections, decoded.
template <class T>
struct Geometry {
  std::array<T, 6> bounds;  // the root box: min x, y, z, max x, y, z (header bounds_value)
  std::vector<uint64_t> nodes;
  std::vector<uint32_t> lists;
  std::vector<std::array<T, 12>> tris;  // unit-triangle transforms, row-major 3x4
  std::vector<T> normal_len;            // |(B-A) x (C-A)| per triangle (shading)
  std::vector<uint32_t> material;       // material index per triangle
  std::vector<std::array<T, 3>> kd;     // diffuse colour per material
  // Scene lighting (docs/architecture.md, "Lighting"); empty lights: the headlight.
  std::vector<std::array<T, 3>> normal;  // unit geometric normal n / |n| per triangle
  std::vector<std::array<T, 3>> ks;      // specular colour per material
  std::vector<uint32_t> ns;              // Blinn-Phong exponent per material, an integer
  std::vector<T> mirror;                 // mirror reflection weight per material
  std::vector<T> transmit;               // refraction weight per material
  std::vector<T> eta_enter, eta_leave;   // ratio of refraction into (1 / ior) and out of (ior)
  struct Light {
    bool directional = false;
    std::array<T, 3> pos;    // point: the position; directional: the unit vector toward it
    std::array<T, 3> color;  // colour x intensity per channel
  };
  std::vector<Light> lights;
  T t_eps = T::zero();  // a shadow ray's hits need t_eps < t
};

template <class T>
struct Ray {
  std::array<T, 3> org, dir;
  T inv_len;  // 1/|dir|, for shading
};

template <class T>
struct Hit {
  int32_t tri = -1;  // triangle index (OBJ order), -1: miss
  T t, u, v, dz;     // distance, barycentrics, d'z of the hit triangle
};

// What the hardware counts (per packet, summed per frame).
struct Counters {
  uint64_t packets = 0;
  uint64_t rays = 0;
  uint64_t nodes_fetched = 0;    // node-port reads: one per inner-node visit (its two children)
  uint64_t inner_visits = 0;     // inner nodes visited by packets
  uint64_t traversal_steps = 0;  // inner node visits x active rays (one sub-unit step each)
  uint64_t leaf_visits = 0;      // leaves visited by packets
  uint64_t empty_leaves = 0;     // of those, leaves without triangles
  uint64_t list_entries = 0;     // list entries read (one per triangle of a visited leaf)
  uint64_t triangle_tests = 0;   // ray-triangle tests (list entries x active rays)
  uint64_t stack_pushes = 0;
  uint64_t stack_pops = 0;
  uint64_t culled_pops = 0;  // popped entries whose every ray was culled
  uint64_t max_stack = 0;    // deepest stack seen
  uint64_t errors = 0;       // packets that ended with an error bit
  uint32_t error_bits = 0;   // OR of every packet's error bits

  void add(const Counters& o) {
    packets += o.packets;
    rays += o.rays;
    nodes_fetched += o.nodes_fetched;
    inner_visits += o.inner_visits;
    traversal_steps += o.traversal_steps;
    leaf_visits += o.leaf_visits;
    empty_leaves += o.empty_leaves;
    list_entries += o.list_entries;
    triangle_tests += o.triangle_tests;
    stack_pushes += o.stack_pushes;
    stack_pops += o.stack_pops;
    culled_pops += o.culled_pops;
    max_stack = max_stack > o.max_stack ? max_stack : o.max_stack;
    errors += o.errors;
    error_bits |= o.error_bits;
  }
};

// d'z = (m8*d.x + m9*d.y) + m10*d.z: the ray's direction along the triangle's normal in its unit
// frame (intersect() below, and the lighting's facing normal from a hit record).
template <class T>
T transformed_dz(const std::array<T, 12>& m, const std::array<T, 3>& d) {
  return (m[8] * d[0] + m[9] * d[1]) + m[10] * d[2];
}

// One ray against one triangle (the intersection unit's fixed operation order):
//   o' = M (o, 1), d' = M d, each row as ((m0*x + m1*y) + m2*z) [+ m3]
//   t = (-o'z) / d'z, u = o'x + t*d'x, v = o'y + t*d'y
// Fills h and returns true when the hit is accepted: t_lo < t, 0 <= u, 0 <= v, u + v <= 1,
// tri != *exclude (when exclude is given), and (t < best.t, or t == best.t and tri < best.tri). A
// primary ray has t_lo = 0 and no excluded triangle; a shadow ray t_lo = t_eps and the triangle it
// starts on.
template <class T>
bool intersect(const std::array<T, 12>& m, const Ray<T>& r, int32_t tri, const Hit<T>& best,
               Hit<T>& h, T t_lo = T::zero(), const int32_t* exclude = nullptr) {
  const auto& o = r.org;
  const auto& d = r.dir;
  const T ox = ((m[0] * o[0] + m[1] * o[1]) + m[2] * o[2]) + m[3];
  const T oy = ((m[4] * o[0] + m[5] * o[1]) + m[6] * o[2]) + m[7];
  const T oz = ((m[8] * o[0] + m[9] * o[1]) + m[10] * o[2]) + m[11];
  const T dx = (m[0] * d[0] + m[1] * d[1]) + m[2] * d[2];
  const T dy = (m[4] * d[0] + m[5] * d[1]) + m[6] * d[2];
  const T dz = transformed_dz(m, d);
  const T t = (-oz) / dz;
  const T u = ox + t * dx;
  const T v = oy + t * dy;
  const T zero = T::zero(), one = T::one();
  if (!(lt(t_lo, t) && le(zero, u) && le(zero, v) && le(u + v, one))) return false;
  if (exclude != nullptr && tri == *exclude) return false;
  if (!(lt(t, best.t) || (eq(t, best.t) && tri < best.tri))) return false;
  h.tri = tri;
  h.t = t;
  h.u = u;
  h.v = v;
  h.dz = dz;
  return true;
}

// Ray set-up (one ray): the reciprocal direction and the interval clipped to the root box.
// Per axis the slab [lo, hi] gives t0 = (lo - o) * inv and t1 = (hi - o) * inv; if either is NaN
// (the origin lies in a face plane and the direction component is zero) the axis does not restrict
// the ray. The interval is [max(0, min(t0, t1) per axis), min(+inf, max(t0, t1) per axis)], axes
// in order x, y, z; then tmax = min(tmax, tlim) (a shadow ray's limit, the light's distance;
// +inf for every other ray, which changes nothing); the ray is active when tmin <= tmax.
template <class T>
struct RaySetup {
  std::array<T, 3> inv;
  T tmin, tmax;
  bool active;
};

template <class T>
RaySetup<T> setup_ray(const Ray<T>& r, const std::array<T, 6>& bounds, T tlim = T::inf()) {
  RaySetup<T> s;
  const T one = T::one();
  for (int a = 0; a < 3; ++a) s.inv[a] = one / r.dir[a];
  s.tmin = T::zero();
  s.tmax = T::inf();
  for (int a = 0; a < 3; ++a) {
    const T t0 = (bounds[a] - r.org[a]) * s.inv[a];
    const T t1 = (bounds[a + 3] - r.org[a]) * s.inv[a];
    if (t0.is_nan() || t1.is_nan()) continue;
    s.tmin = max(s.tmin, min(t0, t1));
    s.tmax = min(s.tmax, max(t0, t1));
  }
  s.tmax = min(s.tmax, tlim);
  s.active = le(s.tmin, s.tmax);
  return s;
}

// One traversal step (one ray, one inner node): t = (split - org[axis]) * inv[axis] and which of
// the ray's near and far children get which interval.
enum class StepCase : uint8_t {
  kBothWhole,  // t is NaN (ray in the split plane): near and far get [tmin, tmax]
  kNearOnly,   // tmax < t: near gets [tmin, tmax]
  kFarOnly,    // t < tmin: far gets [tmin, tmax]
  kBothSplit,  // near gets [tmin, t], far gets [t, tmax]
};

template <class T>
struct StepResult {
  T t;
  StepCase which;
};

template <class T>
StepResult<T> trav_step(T split, T org, T inv, T tmin, T tmax) {
  const T t = (split - org) * inv;
  if (t.is_nan()) return {t, StepCase::kBothWhole};
  if (lt(tmax, t)) return {t, StepCase::kNearOnly};
  if (lt(t, tmin)) return {t, StepCase::kFarOnly};
  return {t, StepCase::kBothSplit};
}

// What a secondary packet's rays carry beside the primary rule (docs/architecture.md,
// "Lighting" and "Reflection"): per ray the lower bound of its hits' t, the triangle it starts on
// (never hit) and its limit t_hi, which ends its interval at set-up and is its initial best t
// (a shadow ray's: the light's distance, so only hits before the light occlude; a bounce ray's:
// +inf); and for shadow rays any-hit termination (a ray with a hit is culled at the next pop).
template <class T>
struct SecondaryLimits {
  T t_lo;
  std::array<int32_t, kPacketRays> exclude{-1, -1, -1, -1};
  std::array<T, kPacketRays> t_hi;
  bool any_hit = true;  // a shadow packet; false: a bounce packet (closest hit)
};

// Traces one packet of up to four rays (valid_mask bit r set: ray r exists) through the tree.
// Returns the error bits (0 on success). The rules are those of docs/architecture.md. With
// limits (a secondary packet), each ray's best starts at {t_hi, -1}, hits need t_lo < t and not
// the excluded triangle, and with any_hit a ray with a hit is culled at the next pop.
template <class T>
uint32_t trace_packet(const Geometry<T>& g, const std::array<Ray<T>, kPacketRays>& rays,
                      uint32_t valid_mask, std::array<Hit<T>, kPacketRays>& hits, Counters& c,
                      const SecondaryLimits<T>* shadow = nullptr) {
  constexpr int kStackDepth = static_cast<int>(spec::kKdtreeStackDepth);
  struct Entry {
    uint32_t node, mask;
    std::array<T, kPacketRays> tmin, tmax;
  };
  std::array<Entry, kStackDepth> stack;
  int sp = 0;

  std::array<std::array<T, 3>, kPacketRays> inv;  // per ray: 1/d per component
  Entry cur{0, 0, {}, {}};
  for (int r = 0; r < kPacketRays; ++r) {
    hits[r] = Hit<T>{};
    hits[r].t = shadow ? shadow->t_hi[r] : T::inf();
    if (!(valid_mask >> r & 1)) continue;
    ++c.rays;
    const RaySetup<T> su = setup_ray(rays[r], g.bounds, shadow ? shadow->t_hi[r] : T::inf());
    inv[r] = su.inv;
    cur.tmin[r] = su.tmin;
    cur.tmax[r] = su.tmax;
    if (su.active) cur.mask |= 1u << r;
  }
  ++c.packets;
  const auto fail = [&](uint32_t bits) {
    for (auto& h : hits) h = Hit<T>{};
    ++c.errors;
    c.error_bits |= bits;
    return bits;
  };

  while (true) {
    if (cur.mask != 0) {
      if (cur.node >= g.nodes.size()) return fail(kErrMalformedNode);
      const Node n = decode_node(g.nodes[cur.node]);
      if (n.kind < 3) {
        // Inner node.
        const T split = T::from_bits(n.upper);
        // Children come after their parent (so every descent makes progress and a malformed
        // image cannot loop), both inside the node section; the split is a finite value.
        if (n.upper > T::kMask || split.is_nan() || split.is_inf() || n.index <= cur.node ||
            static_cast<uint64_t>(n.index) + 1 >= g.nodes.size())
          return fail(kErrMalformedNode);
        ++c.inner_visits;
        ++c.nodes_fetched;  // the read of its two children (the root comes with the configuration)
        // The packet's order: the near child of the lowest-numbered active ray comes first.
        int lead = 0;
        while (!(cur.mask >> lead & 1)) ++lead;
        const uint32_t first = rays[lead].dir[n.kind].sign() ? n.index + 1 : n.index;
        const uint32_t second = first == n.index ? n.index + 1 : n.index;
        Entry a{first, 0, {}, {}}, b{second, 0, {}, {}};  // the packet's first and second child
        for (int r = 0; r < kPacketRays; ++r) {
          if (!(cur.mask >> r & 1)) continue;
          ++c.traversal_steps;
          const T lo = cur.tmin[r], hi = cur.tmax[r];
          const StepResult<T> st = trav_step(split, rays[r].org[n.kind], inv[r][n.kind], lo, hi);
          const uint32_t near = rays[r].dir[n.kind].sign() ? n.index + 1 : n.index;
          Entry& en = near == first ? a : b;  // this ray's near child
          Entry& ef = near == first ? b : a;  // this ray's far child
          const bool to_near = st.which != StepCase::kFarOnly;
          const bool to_far = st.which != StepCase::kNearOnly;
          const bool split_at_t = st.which == StepCase::kBothSplit;
          if (to_near) en.mask |= 1u << r, en.tmin[r] = lo, en.tmax[r] = split_at_t ? st.t : hi;
          if (to_far) ef.mask |= 1u << r, ef.tmin[r] = split_at_t ? st.t : lo, ef.tmax[r] = hi;
        }
        if (a.mask != 0 && b.mask != 0) {
          if (sp == kStackDepth) return fail(kErrStackOverflow);
          stack[sp++] = b;
          ++c.stack_pushes;
          if (static_cast<uint64_t>(sp) > c.max_stack) c.max_stack = static_cast<uint64_t>(sp);
          cur = a;
        } else {
          cur = a.mask != 0 ? a : b;
        }
        continue;
      }
      // Leaf: every triangle of the list against every active ray, one ray after the other.
      ++c.leaf_visits;
      if (n.upper == 0) ++c.empty_leaves;
      if (static_cast<uint64_t>(n.index) + n.upper > g.lists.size()) return fail(kErrBadAddress);
      for (uint32_t k = 0; k < n.upper; ++k) {
        const uint32_t tri = g.lists[n.index + k];
        ++c.list_entries;
        if (tri >= g.tris.size()) return fail(kErrBadAddress);
        for (int r = 0; r < kPacketRays; ++r) {
          if (!(cur.mask >> r & 1)) continue;
          ++c.triangle_tests;
          Hit<T> h;
          if (intersect(g.tris[tri], rays[r], static_cast<int32_t>(tri), hits[r], h,
                        shadow ? shadow->t_lo : T::zero(), shadow ? &shadow->exclude[r] : nullptr))
            hits[r] = h;
        }
      }
    }
    // Pop: rays whose interval starts beyond their closest hit so far are culled.
    if (sp == 0) return 0;
    cur = stack[--sp];
    ++c.stack_pops;
    for (int r = 0; r < kPacketRays; ++r)
      if ((cur.mask >> r & 1) &&
          (!le(cur.tmin[r], hits[r].t) || (shadow && shadow->any_hit && hits[r].tri >= 0)))
        cur.mask &= ~(1u << r);
    if (cur.mask == 0) ++c.culled_pops;
  }
}

// min(max(x, 0), 1) * scale (format operations) rounded to the nearest integer, ties to even
// (exact: the format's value as a double); a NaN gives 0. to_u8 (scale 255) and the lighting's
// fixed point (scale 2^fixed_bits) share it.
template <class T>
uint32_t clamp_scale_round(T x, T scale) {
  T v = max(x, T::zero());
  if (v.is_nan()) return 0;
  v = min(v, T::one()) * scale;
  const double dv = v.to_double();
  double ip = static_cast<double>(static_cast<uint32_t>(dv));
  const double frac = dv - ip;
  if (frac > 0.5 || (frac == 0.5 && (static_cast<uint32_t>(ip) & 1u))) ip += 1.0;
  return static_cast<uint32_t>(ip);
}

// Headlight shading of one hit (docs/architecture.md, "Shading"):
//   c = min(|(d'z * nlen) * inv_len|, 1), f = ambient + (1 - ambient) * c, channel = Kd * f,
//   byte = round_to_nearest_even(min(max(channel, 0), 1) * 255)    (to_u8, below).
template <class T>
uint8_t to_u8(T x) {
  return static_cast<uint8_t>(clamp_scale_round(x, T::from_double(255.0)));
}

// The shading constants as format values: ambient and 1 - ambient, each rounded from double once
// (the RTL's ambient_i/diffuse_i take these values).
template <class T>
T shade_ambient() {
  return T::from_double(static_cast<double>(spec::kShadeAmbientPermille) / 1000.0);
}
template <class T>
T shade_diffuse() {
  return T::from_double(1.0 - static_cast<double>(spec::kShadeAmbientPermille) / 1000.0);
}

template <class T>
std::array<uint8_t, 3> shade(const Geometry<T>& g, const Ray<T>& r, const Hit<T>& h) {
  const T ambient = shade_ambient<T>();
  const T diffuse = shade_diffuse<T>();
  const T c = min(((h.dz * g.normal_len[h.tri]) * r.inv_len).abs(), T::one());
  const T f = ambient + diffuse * c;
  const auto& kd = g.kd[g.material[h.tri]];
  return {to_u8(kd[0] * f), to_u8(kd[1] * f), to_u8(kd[2] * f)};
}

// ---- Scene lighting (docs/architecture.md, "Lighting") ----------------------------------------

// The fixed-point scale of a pixel's sums: a term in [0, 1] counts as round(term * 2^fixed_bits).
constexpr uint32_t kLightOne = 1u << spec::kLightFixedBits;

// x^n for an integer n below 2^exponent_bits by square and multiply, low bit first: r = 1, b = x;
// for bit i = 0 .. exponent_bits - 1: if bit i of n is set, r = r * b; then b = b * b.
template <class T>
T pow_int(T x, uint32_t n) {
  T r = T::one(), b = x;
  for (int i = 0; i < static_cast<int>(spec::kLightExponentBits); ++i) {
    if (n >> i & 1u) r = r * b;
    b = b * b;
  }
  return r;
}

// A term as a fixed-point integer: round_to_nearest_even(min(max(x, 0), 1) * 2^fixed_bits),
// NaN -> 0.
template <class T>
uint32_t light_fixed(T x) {
  return clamp_scale_round(x, T::from_double(static_cast<double>(kLightOne)));  // exact scale
}

// A channel's byte from its sum: round_to_nearest_even(min(sum, 2^fixed_bits) * 255 /
// 2^fixed_bits).
inline uint8_t light_byte(uint64_t sum) {
  constexpr int kBits = static_cast<int>(spec::kLightFixedBits);
  const uint64_t x = (sum < kLightOne ? sum : kLightOne) * 255u;
  uint64_t q = x >> kBits;
  const uint64_t rem = x & (kLightOne - 1u), half = kLightOne / 2;
  if (rem > half || (rem == half && (q & 1u))) ++q;
  return static_cast<uint8_t>(q);
}

// A shadow ray's hits need t > t_eps = |root box diagonal| * kShadowEpsScale (double, rounded
// once), and never its own triangle.
constexpr double kShadowEpsScale =
    1.0 / static_cast<double>(uint64_t{1} << spec::kLightShadowEpsLog2);
constexpr uint32_t kLightExponentMax = (1u << spec::kLightExponentBits) - 1;

// The Blinn-Phong exponent of a material's Ns: round_to_nearest_even(Ns), clamped to
// [0, 2^exponent_bits - 1] (NaN: 0).
template <class T>
uint32_t light_exponent(T ns) {
  const double d = ns.to_double();
  if (!(d > 0.0)) return 0;  // NaN too
  if (d >= kLightExponentMax) return kLightExponentMax;
  return static_cast<uint32_t>(std::nearbyint(d));  // the default rounding: nearest, ties even
}

// One light as seen from one primary hit: the shadow ray (present when the light is in front of
// the surface) and the light's contribution per channel if nothing occludes it.
template <class T>
struct LightSample {
  bool present = false;                   // cos > 0: a shadow ray is traced
  Ray<T> ray;                             // from the hit point toward the light (unit direction)
  T t_hi;                                 // the light's distance (+inf for a directional light)
  std::array<uint32_t, 3> term{0, 0, 0};  // fixed-point contribution per channel
  T spec = T::zero();                     // the specular factor (present samples only)
};

// The hit point, the facing unit normal and the unit view direction of a hit (hit_geometry below
// computes them: P = org + t * d, N = -n if 0 < d'z else n, V = d * inv_len, per component).
template <class T>
struct SurfacePoint {
  std::array<T, 3> p, n, v;
  uint32_t material;
};

template <class T>
T dot3(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

// The ambient term per channel, weighted: fix((Kd * ambient) * w).
template <class T>
std::array<uint32_t, 3> ambient_terms(const std::array<T, 3>& kd, T w) {
  const T ambient = shade_ambient<T>();
  return {light_fixed((kd[0] * ambient) * w), light_fixed((kd[1] * ambient) * w),
          light_fixed((kd[2] * ambient) * w)};
}

template <class T>
LightSample<T> light_sample(const SurfacePoint<T>& sp, const typename Geometry<T>::Light& l,
                            const std::array<T, 3>& kd, const std::array<T, 3>& ks, uint32_t ns,
                            T w) {
  LightSample<T> s;
  std::array<T, 3> lh;
  if (l.directional) {
    lh = l.pos;
    s.t_hi = T::inf();
  } else {
    std::array<T, 3> d;
    for (int a = 0; a < 3; ++a) d[a] = l.pos[a] - sp.p[a];
    const T dist2 = dot3(d, d);
    const T inv_dist = T::one() / sqrt(dist2);
    for (int a = 0; a < 3; ++a) lh[a] = d[a] * inv_dist;
    s.t_hi = dist2 * inv_dist;
  }
  const T cos_l = dot3(sp.n, lh);
  if (!lt(T::zero(), cos_l)) return s;  // behind the surface (or NaN): no ray, no light
  s.present = true;
  s.ray.org = sp.p;
  s.ray.dir = lh;
  s.ray.inv_len = T::one();
  std::array<T, 3> hv;
  for (int a = 0; a < 3; ++a) hv[a] = lh[a] - sp.v[a];
  const T nh = dot3(sp.n, hv) * (T::one() / sqrt(dot3(hv, hv)));
  s.spec = lt(T::zero(), nh) ? pow_int(nh, ns) : T::zero();
  for (int c = 0; c < 3; ++c)
    s.term[c] = light_fixed(((kd[c] * cos_l + ks[c] * s.spec) * l.color[c]) * w);
  return s;
}

// The mirror direction of a hit: R = V - (c + c) * N with c = dot(N, V) (per component: the
// product, then the difference).
template <class T>
std::array<T, 3> mirror_dir(const SurfacePoint<T>& sp) {
  const T c = dot3(sp.n, sp.v);
  const T k = c + c;
  std::array<T, 3> r;
  for (int a = 0; a < 3; ++a) r[a] = sp.v[a] - k * sp.n[a];
  return r;
}

// The refraction direction of a hit (docs/architecture.md, "Refraction"), with e the ratio of
// refraction (eta_leave when the ray leaves through the triangle's back, else eta_enter):
// c = dot(N, V), q = 1 - (e * e) * (1 - c * c); if 0 < q: T = e * V - (e * c + sqrt(q)) * N (per
// component: the two products, then the difference); else (total internal reflection, or NaN)
// the mirror direction.
template <class T>
std::array<T, 3> refract_dir(const SurfacePoint<T>& sp, T e) {
  const T c = dot3(sp.n, sp.v);
  const T q = T::one() - (e * e) * (T::one() - c * c);
  if (!lt(T::zero(), q)) return mirror_dir(sp);
  const T k = e * c + sqrt(q);
  std::array<T, 3> r;
  for (int a = 0; a < 3; ++a) r[a] = e * sp.v[a] - k * sp.n[a];
  return r;
}

// The geometry of a hit that the lighting needs (rc_hit_geom computes the same, bit for bit):
// the hit point, the facing normal and the unit view direction (surface_point), the mirror and
// refraction directions (mirror_dir, refract_dir with e = eta_leave when the ray leaves through
// the triangle's back, 0 < d'z, else eta_enter), and the children's weights w * mirror and
// w * transmit, each ray present when its factor and its weight are above 0.
template <class T>
struct HitGeometry {
  bool back = false;  // 0 < d'z: the ray travels along n (leaves the medium)
  std::array<T, 3> p, n, v;
  std::array<T, 3> r, t;  // the mirror and the refraction direction
  T w_mirror, w_refract;
  bool mirror = false, refract = false;
};

template <class T>
HitGeometry<T> hit_geometry(const Ray<T>& ray, T t, T dz, const std::array<T, 3>& n, T eta_enter,
                            T eta_leave, T w, T mirror, T transmit) {
  HitGeometry<T> h;
  // The ray travels along n when d'z > 0 (d'z = (d . n) / |n|^2): the facing normal is -n.
  h.back = lt(T::zero(), dz);
  SurfacePoint<T> sp;
  for (int a = 0; a < 3; ++a) {
    sp.p[a] = ray.org[a] + t * ray.dir[a];
    sp.n[a] = h.back ? -n[a] : n[a];
    sp.v[a] = ray.dir[a] * ray.inv_len;
  }
  h.p = sp.p;
  h.n = sp.n;
  h.v = sp.v;
  h.r = mirror_dir(sp);
  h.t = refract_dir(sp, h.back ? eta_leave : eta_enter);
  h.w_mirror = w * mirror;
  h.w_refract = w * transmit;
  h.mirror = lt(T::zero(), mirror) && lt(T::zero(), h.w_mirror);
  h.refract = lt(T::zero(), transmit) && lt(T::zero(), h.w_refract);
  return h;
}

// What a lit frame needs beyond the geometry: the bounce depth and the background as format
// values (byte / 255 in double, rounded once), the colour a bounce ray that misses sees.
template <class T>
struct LitParams {
  uint32_t max_bounces = static_cast<uint32_t>(spec::kLightMaxBounces);
  std::array<T, 3> background{T::zero(), T::zero(), T::zero()};
};

template <class T>
LitParams<T> lit_params(uint32_t max_bounces, const std::array<uint8_t, 3>& background) {
  LitParams<T> p;
  p.max_bounces = max_bounces;
  for (int c = 0; c < 3; ++c) p.background[c] = T::from_double(background[c] / 255.0);
  return p;
}

// The rays of a pixel's tree: its primary ray and, below a hit, mirror and refraction rays.
enum class TreeRay : uint8_t { kPrimary, kMirror, kRefract };

// A packet's work under the scene's lights (docs/architecture.md, "Lighting", "Reflection" and
// "Refraction"): per ray its base term (a hit's ambient term; a mirror or refraction ray that
// misses: the background's), and per light, in the image's order, one shadow packet of the hits
// that face it (lights no hit faces have none), with each ray's term; and the packet's two
// children: the mirror rays of its hits on mirror materials and the refraction rays of its hits
// on transparent ones, each a packet, lane for lane. Every term carries the ray's weight (1 for a
// primary ray, exactly: x * 1 = x).
template <class T>
struct ShadowPacket {
  uint32_t light = 0;  // the light's index in the image's order
  uint32_t mask = 0;   // bit r: ray r's hit faces the light, so its shadow ray exists
  std::array<Ray<T>, kPacketRays> rays;
  SecondaryLimits<T> lim;
  std::array<std::array<uint32_t, 3>, kPacketRays> term{};  // fixed point, per channel
};

template <class T>
struct BouncePacket {
  TreeRay kind = TreeRay::kMirror;  // mirror or refraction rays
  uint32_t mask = 0;                // bit r: ray r's hit sends one, in lane r
  std::array<Ray<T>, kPacketRays> rays;
  SecondaryLimits<T> lim;             // t_eps, the hit's triangle, t_hi = +inf, closest hit
  std::array<T, kPacketRays> weight;  // the parent's weight x the material's mirror (transmit)
};

template <class T>
struct LitWork {
  TreeRay kind = TreeRay::kPrimary;                         // the packet's rays
  uint32_t mask = 0;                                        // the packet's rays
  uint32_t hit_mask = 0;                                    // of those, rays with a hit
  std::array<int32_t, kPacketRays> tri{-1, -1, -1, -1};     // each ray's hit triangle
  std::array<std::array<uint32_t, 3>, kPacketRays> base{};  // fixed point, per channel
  std::vector<ShadowPacket<T>> shadows;
  BouncePacket<T> bounce;   // the mirror rays
  BouncePacket<T> refract;  // the refraction rays
};

// The child packet of `kind` (mirror or refraction) of a packet's hits at `depth`: a ray for each
// hit whose material's weight x (mirror or transmit) is above 0, while depth < max_bounces.
template <class T>
BouncePacket<T> bounce_packet(const Geometry<T>& g, TreeRay kind, uint32_t hit_mask,
                              const std::array<HitGeometry<T>, kPacketRays>& hg,
                              const std::array<Hit<T>, kPacketRays>& hits, uint32_t depth,
                              const LitParams<T>& lp) {
  BouncePacket<T> b;
  b.kind = kind;
  b.lim.t_lo = g.t_eps;
  b.lim.any_hit = false;
  const bool mirror = kind == TreeRay::kMirror;
  for (int r = 0; r < kPacketRays; ++r) {
    b.lim.t_hi[r] = T::inf();
    b.weight[r] = T::zero();
    if (!(hit_mask >> r & 1) || depth >= lp.max_bounces) continue;
    if (!(mirror ? hg[r].mirror : hg[r].refract)) continue;  // no such ray, or a weight of 0
    b.rays[r].org = hg[r].p;
    b.rays[r].dir = mirror ? hg[r].r : hg[r].t;
    b.rays[r].inv_len = T::one();
    b.lim.exclude[r] = hits[r].tri;
    b.weight[r] = mirror ? hg[r].w_mirror : hg[r].w_refract;
    b.mask |= 1u << r;
  }
  return b;
}

// The work of a primary packet (depth 0, weight == nullptr: every weight 1) or of a mirror or
// refraction packet at depth 1 .. max_bounces (its weights) that ended without an error, from
// its hits.
template <class T>
LitWork<T> lit_work(const Geometry<T>& g, const std::array<Ray<T>, kPacketRays>& rays,
                    uint32_t mask, const std::array<Hit<T>, kPacketRays>& hits,
                    const LitParams<T>& lp, uint32_t depth = 0,
                    const std::array<T, kPacketRays>* weight = nullptr,
                    TreeRay kind = TreeRay::kPrimary) {
  LitWork<T> w;
  w.kind = kind;
  w.mask = mask;
  std::array<SurfacePoint<T>, kPacketRays> sp;
  std::array<HitGeometry<T>, kPacketRays> hg;
  std::array<T, kPacketRays> wt;
  for (int r = 0; r < kPacketRays; ++r) {
    wt[r] = weight ? (*weight)[r] : T::one();
    if (!(mask >> r & 1)) continue;
    if (hits[r].tri < 0) {
      if (depth > 0)
        for (int c = 0; c < 3; ++c) w.base[r][c] = light_fixed(lp.background[c] * wt[r]);
      continue;
    }
    w.hit_mask |= 1u << r;
    w.tri[r] = hits[r].tri;
    const uint32_t mat = g.material[hits[r].tri];
    hg[r] = hit_geometry(rays[r], hits[r].t, hits[r].dz, g.normal[hits[r].tri], g.eta_enter[mat],
                         g.eta_leave[mat], wt[r], g.mirror[mat], g.transmit[mat]);
    sp[r] = {hg[r].p, hg[r].n, hg[r].v, mat};
    w.base[r] = ambient_terms(g.kd[mat], wt[r]);
  }
  for (size_t li = 0; li < g.lights.size(); ++li) {
    ShadowPacket<T> p;
    p.light = static_cast<uint32_t>(li);
    p.lim.t_lo = g.t_eps;
    for (int r = 0; r < kPacketRays; ++r) {
      p.lim.t_hi[r] = T::inf();
      if (!(w.hit_mask >> r & 1)) continue;
      const uint32_t mat = sp[r].material;
      const LightSample<T> ls =
          light_sample(sp[r], g.lights[li], g.kd[mat], g.ks[mat], g.ns[mat], wt[r]);
      if (!ls.present) continue;
      p.rays[r] = ls.ray;
      p.lim.exclude[r] = hits[r].tri;
      p.lim.t_hi[r] = ls.t_hi;
      p.term[r] = ls.term;
      p.mask |= 1u << r;
    }
    if (p.mask != 0) w.shadows.push_back(p);
  }
  w.bounce = bounce_packet(g, TreeRay::kMirror, w.hit_mask, hg, hits, depth, lp);
  w.refract = bounce_packet(g, TreeRay::kRefract, w.hit_mask, hg, hits, depth, lp);
  return w;
}

// A primary packet's sums over its ray tree. The sums are integers, so the colour does not depend
// on the order in which the tree's packets finish.
struct LitSums {
  uint32_t hit_mask = 0;  // the primary rays with a hit (their colour is the sums')
  std::array<std::array<uint64_t, 3>, kPacketRays> sum{};
  std::array<uint32_t, kPacketRays> lights{};  // bit l: light l reaches the primary hit
  // The hit triangle of the primary ray's mirror ray and of its refraction ray: -2 no such ray,
  // -1 it missed (or its packet failed).
  std::array<int32_t, kPacketRays> bounce_tri{-2, -2, -2, -2};
  std::array<int32_t, kPacketRays> refract_tri{-2, -2, -2, -2};
};

// The colours of a lit packet (misses get {0, 0, 0} here: the caller gives them the background).
struct LitPacket {
  std::array<std::array<uint8_t, 3>, kPacketRays> rgb{};
  std::array<uint32_t, kPacketRays> lights{};  // bit l: light l reaches the ray's hit
  std::array<int32_t, kPacketRays> bounce_tri{-2, -2, -2, -2};
  std::array<int32_t, kPacketRays> refract_tri{-2, -2, -2, -2};
};

// Adds a packet's work at `depth` to its primary packet's sums, given per shadow packet (in the
// work's order) the rays that reached the light (traced with any-hit termination: no hit; 0 for a
// packet that ended with an error, which lets no light through).
template <class T>
void lit_accumulate(const LitWork<T>& w, const std::vector<uint32_t>& reached, uint32_t depth,
                    LitSums& s) {
  if (depth == 0) s.hit_mask = w.hit_mask;
  if (depth == 1) {
    auto& first = w.kind == TreeRay::kRefract ? s.refract_tri : s.bounce_tri;
    for (int r = 0; r < kPacketRays; ++r)
      if (w.mask >> r & 1) first[r] = w.tri[r];
  }
  for (int r = 0; r < kPacketRays; ++r)
    for (int c = 0; c < 3; ++c) s.sum[r][c] += w.base[r][c];
  for (size_t k = 0; k < w.shadows.size(); ++k) {
    const ShadowPacket<T>& p = w.shadows[k];
    for (int r = 0; r < kPacketRays; ++r) {
      if (!(p.mask >> r & reached[k] >> r & 1u)) continue;
      for (int c = 0; c < 3; ++c) s.sum[r][c] += p.term[r][c];
      if (depth == 0 && p.light < 32) s.lights[r] |= 1u << p.light;
    }
  }
}

// A mirror or refraction packet at depth 1 that ended with an error: its rays add nothing and
// count as misses.
inline void lit_bounce_failed(TreeRay kind, uint32_t mask, LitSums& s) {
  auto& first = kind == TreeRay::kRefract ? s.refract_tri : s.bounce_tri;
  for (int r = 0; r < kPacketRays; ++r)
    if (mask >> r & 1) first[r] = -1;
}

inline LitPacket lit_finish(const LitSums& s) {
  LitPacket out;
  out.lights = s.lights;
  out.bounce_tri = s.bounce_tri;
  out.refract_tri = s.refract_tri;
  for (int r = 0; r < kPacketRays; ++r)
    if (s.hit_mask >> r & 1)
      for (int c = 0; c < 3; ++c) out.rgb[r][c] = light_byte(s.sum[r][c]);
  return out;
}

// The rays of a traced shadow packet that reached the light: no hit, and no error.
template <class T>
uint32_t shadow_reached(uint32_t mask, uint32_t err, const std::array<Hit<T>, kPacketRays>& hits) {
  if (err != 0) return 0;
  uint32_t m = 0;
  for (int r = 0; r < kPacketRays; ++r)
    if ((mask >> r & 1) && hits[r].tri < 0) m |= 1u << r;
  return m;
}

// The counters of a lit frame's secondary rays, per kind.
struct LitCounters {
  Counters shadow, bounce, refract;  // shadow, mirror and refraction rays
  void add(const LitCounters& o) {
    shadow.add(o.shadow);
    bounce.add(o.bounce);
    refract.add(o.refract);
  }
};

// A primary packet shaded with the scene's lights: its ray tree, level by level (each packet's
// shadow packets, then its mirror and refraction packets), counted per kind, and the colours.
template <class T>
LitPacket shade_lit(const Geometry<T>& g, const std::array<Ray<T>, kPacketRays>& rays,
                    uint32_t mask, const std::array<Hit<T>, kPacketRays>& hits,
                    const LitParams<T>& lp, LitCounters& counters) {
  LitSums s;
  std::vector<LitWork<T>> level{lit_work(g, rays, mask, hits, lp)};
  for (uint32_t depth = 0; !level.empty(); ++depth) {
    std::vector<LitWork<T>> deeper;
    for (const LitWork<T>& w : level) {
      std::vector<uint32_t> reached;
      for (const ShadowPacket<T>& p : w.shadows) {
        std::array<Hit<T>, kPacketRays> shits;
        const uint32_t err = trace_packet(g, p.rays, p.mask, shits, counters.shadow, &p.lim);
        reached.push_back(shadow_reached(p.mask, err, shits));
      }
      lit_accumulate(w, reached, depth, s);
      for (const BouncePacket<T>* b : {&w.bounce, &w.refract}) {
        if (b->mask == 0) continue;
        Counters& c = b->kind == TreeRay::kMirror ? counters.bounce : counters.refract;
        std::array<Hit<T>, kPacketRays> bhits;
        if (trace_packet(g, b->rays, b->mask, bhits, c, &b->lim) != 0) {
          if (depth == 0) lit_bounce_failed(b->kind, b->mask, s);
          continue;
        }
        deeper.push_back(lit_work(g, b->rays, b->mask, bhits, lp, depth + 1, &b->weight, b->kind));
      }
    }
    level = std::move(deeper);
  }
  return lit_finish(s);
}

}  // namespace rc
