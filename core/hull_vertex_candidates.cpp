#include "core/hull_vertex_candidates.h"

#include <algorithm>

#include "core/exact_predicates.h"

namespace soiq {
namespace {

struct Item {
  double a, b, c;  // the plane coordinate, the row coordinate, the value within the row
  int64_t index;
};

bool less_abc(const Item& x, const Item& y) {
  if (x.a != y.a) return x.a < y.a;
  if (x.b != y.b) return x.b < y.b;
  return x.c < y.c;
}

// Turn of o -> p -> q in the (b, c) plane: > 0 counter-clockwise.
int turn(const Item& o, const Item& p, const Item& q) { return orient2d_sign(o.b, o.c, p.b, p.c, q.b, q.c); }

// Marks in `vertex` the strict 2D hull vertices of one plane given by its row ends (sorted by (b, c),
// distinct): Andrew's monotone chain, collinear points popped.
void mark_plane_hull(const std::vector<Item>& ends, std::vector<Item>& chain, std::vector<char>& vertex) {
  if (ends.size() <= 2) {
    for (const Item& e : ends) vertex[size_t(e.index)] = 1;
    return;
  }
  for (int pass = 0; pass < 2; ++pass) {  // lower chain forwards, upper chain backwards
    chain.clear();
    for (size_t n = 0; n < ends.size(); ++n) {
      const Item& p = pass == 0 ? ends[n] : ends[ends.size() - 1 - n];
      while (chain.size() >= 2 && turn(chain[chain.size() - 2], chain.back(), p) <= 0) chain.pop_back();
      chain.push_back(p);
    }
    for (const Item& e : chain) vertex[size_t(e.index)] = 1;
  }
}

}  // namespace

std::vector<int64_t> hull_vertex_candidates(const std::vector<Vec3>& points) {
  const size_t n = points.size();
  std::vector<char> keep(n, 0), vertex(n, 0);
  std::vector<Item> items(n), ends, chain;
  for (int family = 0; family < 3; ++family) {
    // Family 0: planes of constant x (rows of constant y); 1: constant y (rows z); 2: constant z (rows x).
    const int a = family, b = (family + 1) % 3, c = (family + 2) % 3;
    if (family == 0) {
      for (size_t p = 0; p < n; ++p) items[p] = {points[p][a], points[p][b], points[p][c], int64_t(p)};
    } else {
      for (Item& it : items) {
        const Vec3& p = points[size_t(it.index)];
        it = {p[a], p[b], p[c], it.index};
      }
    }
    // The index breaks ties so that duplicates keep their lowest index in every family.
    std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) {
      if (less_abc(x, y)) return true;
      if (less_abc(y, x)) return false;
      return x.index < y.index;
    });
    std::fill(vertex.begin(), vertex.end(), char(0));
    for (size_t s = 0; s < n;) {
      size_t e = s;
      ends.clear();
      while (e < n && items[e].a == items[s].a) {
        // One row: its first and last distinct points (a middle one lies between them).
        size_t r = e;
        while (r < n && items[r].a == items[e].a && items[r].b == items[e].b) ++r;
        ends.push_back(items[e]);
        size_t last = r - 1;
        while (last > e && items[last - 1].c == items[last].c) --last;  // lowest index of the duplicates
        if (items[last].c != items[e].c) ends.push_back(items[last]);
        e = r;
      }
      mark_plane_hull(ends, chain, vertex);
      s = e;
    }
    for (size_t p = 0; p < n; ++p) keep[p] = char(family == 0 ? vertex[p] : keep[p] & vertex[p]);
  }
  std::vector<int64_t> out;
  for (size_t p = 0; p < n; ++p) {
    if (keep[p]) out.push_back(int64_t(p));
  }
  return out;
}

}  // namespace soiq
