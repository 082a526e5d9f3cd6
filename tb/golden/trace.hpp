// The golden model of the ray tracing core: packet kd-tree traversal, list walking, intersection
// through the unit-triangle transform, closest hit, shading. Every rule here is specified in
// docs/architecture.md ("The core's rules"); the RTL implements exactly these rules, so every
// arithmetic operation is a format operation (rc::Fp) in the order written.
#pragma once

#include <array>
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

// One ray against one triangle (the intersection unit's fixed operation order):
//   o' = M (o, 1), d' = M d, each row as ((m0*x + m1*y) + m2*z) [+ m3]
//   t = (-o'z) / d'z, u = o'x + t*d'x, v = o'y + t*d'y
// Fills h and returns true when the hit is accepted: 0 < t, 0 <= u, 0 <= v, u + v <= 1, and
// (t < best.t, or t == best.t and tri < best.tri).
template <class T>
bool intersect(const std::array<T, 12>& m, const Ray<T>& r, int32_t tri, const Hit<T>& best,
               Hit<T>& h) {
  const auto& o = r.org;
  const auto& d = r.dir;
  const T ox = ((m[0] * o[0] + m[1] * o[1]) + m[2] * o[2]) + m[3];
  const T oy = ((m[4] * o[0] + m[5] * o[1]) + m[6] * o[2]) + m[7];
  const T oz = ((m[8] * o[0] + m[9] * o[1]) + m[10] * o[2]) + m[11];
  const T dx = (m[0] * d[0] + m[1] * d[1]) + m[2] * d[2];
  const T dy = (m[4] * d[0] + m[5] * d[1]) + m[6] * d[2];
  const T dz = (m[8] * d[0] + m[9] * d[1]) + m[10] * d[2];
  const T t = (-oz) / dz;
  const T u = ox + t * dx;
  const T v = oy + t * dy;
  const T zero = T::zero(), one = T::one();
  if (!(lt(zero, t) && le(zero, u) && le(zero, v) && le(u + v, one))) return false;
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
// in order x, y, z; the ray is active when tmin <= tmax.
template <class T>
struct RaySetup {
  std::array<T, 3> inv;
  T tmin, tmax;
  bool active;
};

template <class T>
RaySetup<T> setup_ray(const Ray<T>& r, const std::array<T, 6>& bounds) {
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

// Traces one packet of up to four rays (valid_mask bit r set: ray r exists) through the tree.
// Returns the error bits (0 on success). The rules are those of docs/architecture.md.
template <class T>
uint32_t trace_packet(const Geometry<T>& g, const std::array<Ray<T>, kPacketRays>& rays,
                      uint32_t valid_mask, std::array<Hit<T>, kPacketRays>& hits, Counters& c) {
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
    hits[r].t = T::inf();
    if (!(valid_mask >> r & 1)) continue;
    ++c.rays;
    const RaySetup<T> su = setup_ray(rays[r], g.bounds);
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
          if (intersect(g.tris[tri], rays[r], static_cast<int32_t>(tri), hits[r], h)) hits[r] = h;
        }
      }
    }
    // Pop: rays whose interval starts beyond their closest hit so far are culled.
    if (sp == 0) return 0;
    cur = stack[--sp];
    ++c.stack_pops;
    for (int r = 0; r < kPacketRays; ++r)
      if ((cur.mask >> r & 1) && !le(cur.tmin[r], hits[r].t)) cur.mask &= ~(1u << r);
    if (cur.mask == 0) ++c.culled_pops;
  }
}

// Headlight shading of one hit (docs/architecture.md, "Shading"):
//   c = min(|(d'z * nlen) * inv_len|, 1), f = ambient + (1 - ambient) * c, channel = Kd * f,
//   byte = round_to_nearest_even(min(max(channel, 0), 1) * 255).
template <class T>
uint8_t to_u8(T x) {
  const T zero = T::zero(), one = T::one();
  T v = max(x, zero);
  if (v.is_nan()) return 0;
  v = min(v, one) * T::from_double(255.0);
  // v is in [0, 255]: round to the nearest integer, ties to even (exact: the format's double).
  const double dv = v.to_double();
  double ip = static_cast<double>(static_cast<uint32_t>(dv));
  const double frac = dv - ip;
  if (frac > 0.5 || (frac == 0.5 && (static_cast<uint32_t>(ip) & 1u))) ip += 1.0;
  return static_cast<uint8_t>(ip);
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

}  // namespace rc
