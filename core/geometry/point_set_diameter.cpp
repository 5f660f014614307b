#include "core/geometry/point_set_diameter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace soiq {
namespace {

constexpr size_t kLeafSize = 8;  // measured: 8 beats 4, 16 and 32 on marching-cubes hulls

struct Node {
  Vec3 lo, hi;          // bounding box of the node's points (exact)
  size_t begin, end;    // range in the permuted order
  int32_t left, right;  // children; -1 for a leaf or a node not split yet
};

// A good first lower bound: from any point to its farthest, then that one's farthest. Returns the
// squared distance and the pair.
double farthest_pair_squared(const std::vector<Vec3>& points, size_t& a, size_t& b) {
  size_t from = 0;
  double best = 0;
  a = b = 0;
  for (int round = 0; round < 2; ++round) {
    size_t far = from;
    for (size_t n = 0; n < points.size(); ++n) {
      const Vec3 d = points[from] - points[n];
      if (dot(d, d) > best) best = dot(d, d), far = n, a = from, b = n;
    }
    from = far;
  }
  return best;
}

class DiameterSearch {
 public:
  // The tree is built over a copy of the points, permuted in place (median splits move values,
  // not indices, so no comparison reads memory through an index), and only as deep as the search
  // goes: a node is split when a pair it is in survives the bound, so the parts pruned near the
  // root are never sorted.
  // `best_squared`: a squared distance some pair of the whole set reaches (a lower bound).
  DiameterSearch(const std::vector<Vec3>& points, double best_squared) : sorted_(points), best_(best_squared) {
    // Each split leaves at least kLeafSize / 2 points per child: this many nodes at most, so
    // references into nodes_ stay valid while the search adds nodes.
    nodes_.reserve(2 * (points.size() / (kLeafSize / 2) + 1));
    nodes_.push_back(make_node(0, points.size()));
  }

  double run() {
    visit(0, 0);
    return std::sqrt(best_);
  }

 private:
  Node make_node(size_t begin, size_t end) const {
    Node node{sorted_[begin], sorted_[begin], begin, end, -1, -1};
    for (size_t n = begin; n < end; ++n) {
      for (int a = 0; a < 3; ++a) {
        node.lo[a] = std::min(node.lo[a], sorted_[n][a]);
        node.hi[a] = std::max(node.hi[a], sorted_[n][a]);
      }
    }
    return node;
  }

  static bool is_leaf(const Node& node) { return node.end - node.begin <= kLeafSize; }

  // Splits a node at the median of its box's longest axis, once.
  void split(int32_t id) {
    Node& node = nodes_[size_t(id)];
    if (node.left >= 0) return;
    const Vec3 extent = node.hi - node.lo;
    const int axis = int(std::max_element(extent.begin(), extent.end()) - extent.begin());
    const size_t mid = node.begin + (node.end - node.begin) / 2;
    std::nth_element(sorted_.begin() + long(node.begin), sorted_.begin() + long(mid), sorted_.begin() + long(node.end),
                     [axis](const Vec3& x, const Vec3& y) { return x[axis] < y[axis]; });
    node.left = int32_t(nodes_.size());
    nodes_.push_back(make_node(node.begin, mid));
    node.right = int32_t(nodes_.size());
    nodes_.push_back(make_node(mid, node.end));
  }

  // Upper bound on the squared distance between any point of box a and any point of box b.
  static double max_squared_between(const Node& a, const Node& b) {
    double s = 0;
    for (int k = 0; k < 3; ++k) {
      const double d = std::max(std::fabs(a.hi[k] - b.lo[k]), std::fabs(b.hi[k] - a.lo[k]));
      s += d * d;
    }
    return s;
  }

  void visit(int32_t ia, int32_t ib) {
    const Node& a = nodes_[size_t(ia)];
    const Node& b = nodes_[size_t(ib)];
    // The bound is computed in floating point too: keep a margin so rounding never drops the pair
    // an all-pairs loop would return.
    if (max_squared_between(a, b) * (1 + 1e-12) <= best_) return;
    const bool a_leaf = is_leaf(a), b_leaf = is_leaf(b);
    if (a_leaf && b_leaf) {
      double best = best_;
      for (size_t x = a.begin; x < a.end; ++x) {
        const Vec3 p = sorted_[x];
        for (size_t y = (ia == ib ? x + 1 : b.begin); y < b.end; ++y) {
          const Vec3 d = p - sorted_[y];
          const double s = dot(d, d);
          best = s > best ? s : best;
        }
      }
      best_ = best;
      return;
    }
    if (ia == ib) {  // a pair of a node with itself: its children's three pairs
      split(ia);
      visit(a.left, a.left);
      visit(a.left, a.right);
      visit(a.right, a.right);
      return;
    }
    // Split the larger (or the only inner) node.
    const bool split_a = !a_leaf && (b_leaf || a.end - a.begin >= b.end - b.begin);
    split(split_a ? ia : ib);
    // The more promising child first: a larger best found early prunes more of the rest.
    const int32_t keep = split_a ? ib : ia, l = split_a ? a.left : b.left, r = split_a ? a.right : b.right;
    const Node& other = nodes_[size_t(keep)];
    const bool left_first =
        max_squared_between(nodes_[size_t(l)], other) >= max_squared_between(nodes_[size_t(r)], other);
    for (const int32_t child : {left_first ? l : r, left_first ? r : l}) {
      if (split_a) {
        visit(child, ib);
      } else {
        visit(ia, child);
      }
    }
  }

  std::vector<Vec3> sorted_;  // the points in tree order: a leaf's points are contiguous
  std::vector<Node> nodes_;
  double best_;
};

}  // namespace

double point_set_diameter(const std::vector<Vec3>& points_mm) {
  if (points_mm.size() < 2) return 0;
  // A lower bound first (farthest_pair_squared), then a filter: for a centre c and R the largest
  // |q - c|, any pair p, q has |p - q| <= |p - c| + R, so a point closer to c than best - R is in
  // no pair longer than best. Two centres are tried, the bounding box's and the midpoint of the
  // pair found, and the one with the smaller R taken: on an elongated or lumpy structure the
  // midpoint's R is near best / 2 and only the structure's ends stay; on a sphere the outermost
  // layer does. The margin covers the rounding of every distance here many times over, so no point
  // of the longest pair is ever dropped.
  size_t a = 0, b = 0;
  const double best_squared = farthest_pair_squared(points_mm, a, b);
  Vec3 lo = points_mm[0], hi = points_mm[0];
  for (const Vec3& p : points_mm) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  const Vec3 box_centre = 0.5 * (lo + hi), pair_centre = 0.5 * (points_mm[a] + points_mm[b]);
  double box_r2 = 0, pair_r2 = 0;
  for (const Vec3& p : points_mm) {
    box_r2 = std::max(box_r2, dot(p - box_centre, p - box_centre));
    pair_r2 = std::max(pair_r2, dot(p - pair_centre, p - pair_centre));
  }
  const Vec3 c = pair_r2 < box_r2 ? pair_centre : box_centre;
  const double best = std::sqrt(best_squared), r = std::sqrt(std::min(pair_r2, box_r2));
  const double reach = (best - r) - 1e-9 * (best + r);
  if (reach <= 0) return DiameterSearch(points_mm, best_squared).run();
  std::vector<Vec3> far;
  for (const Vec3& p : points_mm) {
    if (dot(p - c, p - c) >= reach * reach) far.push_back(p);
  }
  if (far.size() < 2) return best;
  return DiameterSearch(far, best_squared).run();
}

}  // namespace soiq
