#include "kdtree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "error.hpp"

namespace rc::scene {

double surface_area(const Box& b) {
  const glm::dvec3 d = b.hi - b.lo;
  return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One triangle's clipped extent on one axis: its minimum (in a "lo" list) or its maximum (in a
// "hi" list). Each node keeps six lists (lo and hi per axis) sorted by (pos, tri); together they
// are Wald and Havran's sorted event lists, with a planar triangle appearing as lo == hi.
struct Entry {
  double pos;
  uint32_t tri;
};

bool entry_less(const Entry& a, const Entry& b) {
  return a.pos < b.pos || (a.pos == b.pos && a.tri < b.tri);
}

struct Lists {
  std::vector<Entry> lo[3], hi[3];
  size_t size() const { return lo[0].size(); }
  std::vector<Entry>& list(int axis, int which) { return which == 0 ? lo[axis] : hi[axis]; }
};

enum : uint8_t { kLeft = 1, kRight = 2, kBoth = 3 };

struct Split {
  int axis = -1;
  double pos = 0.0;
  double cost = kInf;
};

void release(std::vector<Entry>* v) { std::vector<Entry>().swap(*v); }

// Sutherland-Hodgman against one axis-aligned plane; points on the plane are kept. Intersection
// points get the plane's coordinate exactly on the clipping axis.
int clip_plane(const glm::dvec3* in, int n, glm::dvec3* out, int axis, double b, bool keep_above) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const glm::dvec3& cur = in[i];
    const glm::dvec3& prev = in[(i + n - 1) % n];
    const bool cin = keep_above ? cur[axis] >= b : cur[axis] <= b;
    const bool pin = keep_above ? prev[axis] >= b : prev[axis] <= b;
    if (cin != pin) {
      const double t = (b - prev[axis]) / (cur[axis] - prev[axis]);
      glm::dvec3 p = prev + t * (cur - prev);
      p[axis] = b;
      out[m++] = p;
    }
    if (cin) out[m++] = cur;
  }
  return m;
}

class Builder {
 public:
  Builder(const std::vector<std::array<glm::dvec3, 3>>& tris, const std::vector<uint32_t>& ids,
          const Box& root, const NumberFormat& format, const KdParams& params)
      : tris_(tris), ids_(ids), fmt_(format), p_(params) {
    tree_.bounds = root;
    root_area_ = surface_area(root);
    double scale = 0.0;
    for (int a = 0; a < 3; ++a)
      scale = std::max({scale, std::abs(root.lo[a]), std::abs(root.hi[a])});
    // Rounding errors of the clipping are a few units of 2^-52 of the largest coordinate; the
    // enlargement is far larger than that and far smaller than any format step.
    widen_ = std::ldexp(scale > 0.0 ? scale : 1.0, -32);
    // One unit in the last place of the format at the largest coordinate (a power of two).
    const double big = format.round_up(scale > 0.0 ? scale : 1.0);
    min_extent_ = params.min_extent_ulps * (format.next_up(big) - big);
  }

  KdTree run() {
    const size_t n = tris_.size();
    if (n > KdNode::kMaxIndex)
      throw Error("too many triangles for the node format (" + std::to_string(n) + ")");
    side_.assign(n, 0);
    clip_.resize(n);
    Lists root;
    for (int a = 0; a < 3; ++a) {
      root.lo[a].reserve(n);
      root.hi[a].reserve(n);
    }
    for (size_t i = 0; i < n; ++i) {
      const auto& t = tris_[i];
      for (int a = 0; a < 3; ++a) {
        const double lo = std::min({t[0][a], t[1][a], t[2][a]});
        const double hi = std::max({t[0][a], t[1][a], t[2][a]});
        root.lo[a].push_back({lo, static_cast<uint32_t>(i)});
        root.hi[a].push_back({hi, static_cast<uint32_t>(i)});
      }
    }
    for (int a = 0; a < 3; ++a) {
      std::sort(root.lo[a].begin(), root.lo[a].end(), entry_less);
      std::sort(root.hi[a].begin(), root.hi[a].end(), entry_less);
    }
    tree_.nodes.emplace_back();
    // The gain threshold in the unnormalised units of the split test below: cost x area.
    min_gain_ = p_.min_gain * root_area_ / static_cast<double>(std::max<size_t>(n, 1));
    build(0, tree_.bounds, root, 0);
    return std::move(tree_);
  }

 private:
  Split find_split(const Box& v, const Lists& l) const {
    Split best;
    const double sav = surface_area(v);
    if (!(sav > 0.0)) return best;
    const size_t n = l.size();
    const double ct = p_.traversal_cost, ci = p_.intersection_cost;
    for (int k = 0; k < 3; ++k) {
      const double vmin = v.lo[k], vmax = v.hi[k];
      if (!(vmax > vmin)) continue;
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      const double da = v.hi[a] - v.lo[a], db = v.hi[b] - v.lo[b];
      const double cross = da * db, perim = da + db;
      const double min_empty = p_.empty_min_fraction * (vmax - vmin);
      // Candidates closer than min_extent_ to a face move to that distance (a thin slab that holds
      // the geometry lying on the face is worth having, a slab the traversal cannot resolve is
      // not); clamping keeps the candidate sequence sorted.
      const double s_min = std::max(fmt_.above(vmin), fmt_.round_up(vmin + min_extent_));
      const double s_max = std::min(fmt_.below(vmax), fmt_.round_down(vmax - min_extent_));
      if (!(s_min > vmin && s_max < vmax && s_min <= s_max)) continue;
      const std::vector<Entry>& lo = l.lo[k];
      const std::vector<Entry>& hi = l.hi[k];
      // Candidates: the format value just below each minimum and just above each maximum. Both
      // sequences are non-decreasing, so merging them visits the candidates in order, and two
      // pointers count the triangles with lo <= s and with hi < s.
      size_t i = 0, j = 0, cl = 0, ch = 0;
      double ca = n > 0 ? fmt_.below(lo[0].pos) : kInf;
      double cb = n > 0 ? fmt_.above(hi[0].pos) : kInf;
      double last = -kInf;
      for (;;) {
        double s;
        if (ca <= cb) {
          s = ca;
          ca = ++i < n ? fmt_.below(lo[i].pos) : kInf;
        } else {
          s = cb;
          cb = ++j < n ? fmt_.above(hi[j].pos) : kInf;
        }
        if (s >= vmax) break;  // also the end of both sequences (s = inf)
        s = std::min(std::max(s, s_min), s_max);
        if (s <= last) continue;
        last = s;
        while (cl < n && lo[cl].pos <= s) ++cl;
        while (ch < n && hi[ch].pos < s) ++ch;
        const double nl = static_cast<double>(cl), nr = static_cast<double>(n - ch);
        const double sal = 2.0 * (cross + (s - vmin) * perim);
        const double sar = 2.0 * (cross + (vmax - s) * perim);
        double cost = ct + ci * (sal * nl + sar * nr) / sav;
        if ((cl == 0 && s - vmin >= min_empty) || (ch == n && vmax - s >= min_empty))
          cost *= 1.0 - p_.empty_bonus;
        if (cost < best.cost) best = {k, s, cost};
      }
    }
    return best;
  }

  // The conservative box of triangle t clipped to `child`, given its box `pc` in the parent.
  Box clip(uint32_t t, const Box& child, const Box& pc) const {
    Box fallback;
    fallback.lo = glm::max(pc.lo, child.lo);
    fallback.hi = glm::min(pc.hi, child.hi);
    glm::dvec3 buf[2][16];
    int n = 3;
    for (int k = 0; k < 3; ++k) buf[0][k] = tris_[t][k];
    int cur = 0;
    for (int a = 0; a < 3 && n > 0; ++a) {
      n = clip_plane(buf[cur], n, buf[1 - cur], a, child.lo[a], true);
      cur = 1 - cur;
      n = clip_plane(buf[cur], n, buf[1 - cur], a, child.hi[a], false);
      cur = 1 - cur;
    }
    if (n == 0) return fallback;
    Box r{buf[cur][0], buf[cur][0]};
    for (int k = 1; k < n; ++k) {
      r.lo = glm::min(r.lo, buf[cur][k]);
      r.hi = glm::max(r.hi, buf[cur][k]);
    }
    r.lo = glm::max(r.lo - widen_, fallback.lo);
    r.hi = glm::min(r.hi + widen_, fallback.hi);
    for (int a = 0; a < 3; ++a)
      if (r.lo[a] > r.hi[a]) return fallback;
    return r;
  }

  void make_leaf(uint32_t node, const Box& v, Lists& l, uint32_t depth) {
    const size_t n = l.size();
    const size_t first = tree_.lists.size();
    if (n > 0 && first > KdNode::kMaxIndex)
      throw Error("too many leaf list entries for the node format (more than " +
                  std::to_string(KdNode::kMaxIndex) + ")");
    for (const Entry& e : l.lo[0]) tree_.lists.push_back(ids_[e.tri]);
    std::sort(tree_.lists.begin() + static_cast<std::ptrdiff_t>(first), tree_.lists.end());
    tree_.nodes[node] = n > 0 ? KdNode::leaf(static_cast<uint32_t>(first), static_cast<uint32_t>(n))
                              : KdNode::leaf(0, 0);
    ++tree_.leaves;
    if (n == 0) ++tree_.empty_leaves;
    tree_.max_leaf = std::max(tree_.max_leaf, n);
    tree_.depth = std::max(tree_.depth, depth);
    if (root_area_ > 0.0)
      tree_.sah_cost +=
          p_.intersection_cost * static_cast<double>(n) * surface_area(v) / root_area_;
    for (int a = 0; a < 3; ++a) {
      release(&l.lo[a]);
      release(&l.hi[a]);
    }
  }

  void build(uint32_t node, const Box& v, Lists& l, uint32_t depth) {
    const size_t n = l.size();
    Split best;
    if (n > 0 && depth < static_cast<uint32_t>(p_.max_depth)) best = find_split(v, l);
    const double leaf_cost = p_.intersection_cost * static_cast<double>(n);
    if (best.axis < 0 || best.cost >= leaf_cost ||
        (leaf_cost - best.cost) * surface_area(v) < min_gain_) {
      make_leaf(node, v, l, depth);
      return;
    }
    const int k = best.axis;
    const double s = best.pos;
    for (const Entry& e : l.lo[k]) side_[e.tri] = e.pos <= s ? kLeft : 0;
    for (const Entry& e : l.hi[k])
      if (e.pos >= s) side_[e.tri] |= kRight;
    size_t only_l = 0, only_r = 0, both = 0;
    for (const Entry& e : l.lo[k]) {
      const uint8_t f = side_[e.tri];
      only_l += f == kLeft;
      only_r += f == kRight;
      both += f == kBoth;
    }
    Box vl = v, vr = v;
    vl.hi[k] = s;
    vr.lo[k] = s;
    Lists left, right;
    std::vector<uint32_t> straddle;
    straddle.reserve(both);
    for (int a = 0; a < 3; ++a) {
      for (int w = 0; w < 2; ++w) {
        std::vector<Entry>& src = l.list(a, w);
        std::vector<Entry>& dl = left.list(a, w);
        std::vector<Entry>& dr = right.list(a, w);
        dl.reserve(only_l + both);
        dr.reserve(only_r + both);
        for (const Entry& e : src) {
          switch (side_[e.tri]) {
            case kLeft: dl.push_back(e); break;
            case kRight: dr.push_back(e); break;
            default:
              if (w == 0) {
                clip_[e.tri].lo[a] = e.pos;
                if (a == 0) straddle.push_back(e.tri);
              } else {
                clip_[e.tri].hi[a] = e.pos;
              }
          }
        }
        release(&src);
      }
    }
    if (!straddle.empty()) {
      Lists add_l, add_r;
      for (uint32_t t : straddle) {
        const Box bl = clip(t, vl, clip_[t]);
        const Box br = clip(t, vr, clip_[t]);
        for (int a = 0; a < 3; ++a) {
          add_l.lo[a].push_back({bl.lo[a], t});
          add_l.hi[a].push_back({bl.hi[a], t});
          add_r.lo[a].push_back({br.lo[a], t});
          add_r.hi[a].push_back({br.hi[a], t});
        }
      }
      for (int a = 0; a < 3; ++a) {
        for (int w = 0; w < 2; ++w) {
          merge_into(&left.list(a, w), &add_l.list(a, w));
          merge_into(&right.list(a, w), &add_r.list(a, w));
        }
      }
    }
    const size_t child = tree_.nodes.size();
    if (child + 1 > KdNode::kMaxIndex)
      throw Error("too many kd-tree nodes for the node format (more than " +
                  std::to_string(KdNode::kMaxIndex) + ")");
    tree_.nodes.emplace_back();
    tree_.nodes.emplace_back();
    tree_.nodes[node] = KdNode::inner(k, static_cast<uint32_t>(child), fmt_.encode(s));
    ++tree_.inner;
    if (root_area_ > 0.0) tree_.sah_cost += p_.traversal_cost * surface_area(v) / root_area_;
    build(static_cast<uint32_t>(child), vl, left, depth + 1);
    build(static_cast<uint32_t>(child + 1), vr, right, depth + 1);
  }

  static void merge_into(std::vector<Entry>* dst, std::vector<Entry>* add) {
    std::sort(add->begin(), add->end(), entry_less);
    const auto mid = static_cast<std::ptrdiff_t>(dst->size());
    dst->insert(dst->end(), add->begin(), add->end());
    std::inplace_merge(dst->begin(), dst->begin() + mid, dst->end(), entry_less);
    release(add);
  }

  const std::vector<std::array<glm::dvec3, 3>>& tris_;
  const std::vector<uint32_t>& ids_;
  NumberFormat fmt_;
  KdParams p_;
  KdTree tree_;
  double root_area_ = 0.0;
  double widen_ = 0.0;
  double min_gain_ = 0.0;
  double min_extent_ = 0.0;
  std::vector<uint8_t> side_;
  std::vector<Box> clip_;
};

}  // namespace

KdTree build_kdtree(const std::vector<std::array<glm::dvec3, 3>>& tris,
                    const std::vector<uint32_t>& ids, const Box& root, const NumberFormat& format,
                    const KdParams& params) {
  if (tris.size() != ids.size()) throw Error("internal error: triangle and id counts differ");
  return Builder(tris, ids, root, format, params).run();
}

}  // namespace rc::scene
