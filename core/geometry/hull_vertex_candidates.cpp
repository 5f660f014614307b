#include "core/geometry/hull_vertex_candidates.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstring>
#include <optional>

#include "core/base/cpu_dispatch.h"
#include "core/geometry/dyadic_lattice.h"
#include "core/geometry/exact_predicates.h"
#include "core/geometry/lattice_polygon.h"

namespace soiq {
namespace {

// Order-preserving integer image of a finite coordinate: 2^63 plus or minus its magnitude's bits
// (which order like the magnitude), so x < y iff key(x) < key(y), and -0.0 and +0.0 share one key.
// Unlike flipping a negative's bits, this keeps trailing zero bits zero on both sides of 0, so
// the radix passes over them are skipped for lattice coordinates.
uint64_t key_of(double x) {
  uint64_t u = 0;
  std::memcpy(&u, &x, sizeof u);
  const uint64_t magnitude = u & ~(uint64_t(1) << 63), zero = uint64_t(1) << 63;
  return (u >> 63) != 0 ? zero - magnitude : zero + magnitude;
}

struct Item {
  uint64_t a, b, c;  // keys of the plane coordinate, the row coordinate, the value within the row
  int64_t index;
};

// Sorts by (a, b, c), ties kept in input order: LSD radix sort over 11-bit digits, c's first, with
// the passes whose digit is the same for every item skipped (lattice coordinates share most bits).
void radix_sort(std::vector<Item>& items, std::vector<Item>& buffer) {
  constexpr int kBits = 11, kDigits = 6, kBuckets = 1 << kBits;
  const size_t n = items.size();
  if (n < 2) return;
  auto key_at = [](const Item& it, int key) { return key == 0 ? it.c : key == 1 ? it.b : it.a; };
  // The digits in which some key differs from the first item's: only those need a pass.
  uint64_t varies[3] = {0, 0, 0};
  for (const Item& it : items) {
    for (int key = 0; key < 3; ++key) varies[key] |= key_at(it, key) ^ key_at(items[0], key);
  }
  std::vector<uint32_t> count(kBuckets);
  buffer.resize(n);
  for (int key = 0; key < 3; ++key) {
    for (int d = 0; d < kDigits; ++d) {
      const int shift = kBits * d;
      if (((varies[key] >> shift) & (kBuckets - 1)) == 0) continue;  // one digit value: order unchanged
      std::fill(count.begin(), count.end(), 0u);
      for (const Item& it : items) ++count[(key_at(it, key) >> shift) & (kBuckets - 1)];
      uint32_t sum = 0;
      for (uint32_t& c : count) {
        const uint32_t here = c;
        c = sum, sum += here;
      }
      for (const Item& it : items) buffer[count[(key_at(it, key) >> shift) & (kBuckets - 1)]++] = it;
      items.swap(buffer);
    }
  }
}

// Turn of o -> p -> q in the (b, c) plane: > 0 counter-clockwise.
// A row end in its plane: the row and value coordinates themselves, for exact turns.
struct End {
  double b, c;
  int64_t index;
};

int turn(const End& o, const End& p, const End& q) { return orient2d_sign(o.b, o.c, p.b, p.c, q.b, q.c); }

// Marks in `vertex` the strict 2D hull vertices of one plane given by its row ends (sorted by (b, c),
// distinct): Andrew's monotone chain, collinear points popped.
void mark_plane_hull(const std::vector<End>& ends, std::vector<End>& chain, std::vector<char>& vertex) {
  if (ends.size() <= 2) {
    for (const End& e : ends) vertex[size_t(e.index)] = 1;
    return;
  }
  for (int pass = 0; pass < 2; ++pass) {  // lower chain forwards, upper chain backwards
    chain.clear();
    for (size_t n = 0; n < ends.size(); ++n) {
      const End& p = pass == 0 ? ends[n] : ends[ends.size() - 1 - n];
      while (chain.size() >= 2 && turn(chain[chain.size() - 2], chain.back(), p) <= 0) chain.pop_back();
      chain.push_back(p);
    }
    for (const End& e : chain) vertex[size_t(e.index)] = 1;
  }
}

// The same filter on a small dyadic lattice (dyadic_lattice.h), with integer coordinates and dense
// tables instead of sorts: per family, each (plane, row) cell keeps its row's least and greatest
// value and the lowest index holding each, and each plane's hull is taken over its rows' ends in
// row order. Returns nothing when a family's table would exceed `max_cells`.
std::optional<std::vector<int64_t>> lattice_candidates(const std::vector<Vec3>& points, int exponent,
                                                       int64_t max_cells) {
  const size_t n = points.size();
  std::vector<std::array<int32_t, 3>> q(n);
  std::array<int32_t, 3> lo{INT32_MAX, INT32_MAX, INT32_MAX}, hi{INT32_MIN, INT32_MIN, INT32_MIN};
  const double scale = std::ldexp(1.0, exponent);
  for (size_t i = 0; i < n; ++i) {
    for (size_t a = 0; a < 3; ++a) {
      q[i][a] = int32_t(points[i][a] * scale);  // exact: an integer below 2^15
      lo[a] = std::min(lo[a], q[i][a]), hi[a] = std::max(hi[a], q[i][a]);
    }
  }
  if (n == 0) return std::vector<int64_t>{};
  for (size_t a = 0; a < 3; ++a) {
    // In int64_t: the extents are below 2^16 each, their product far below its range.
    const int64_t width = int64_t(hi[a]) - lo[a] + 1, rows = int64_t(hi[(a + 1) % 3]) - lo[(a + 1) % 3] + 1;
    if (width * rows > max_cells) return std::nullopt;
  }
  struct Cell {
    int32_t least = INT32_MAX, greatest = INT32_MIN;  // values along the row
    int32_t least_index = -1, greatest_index = -1;
  };
  std::vector<Cell> cells;
  std::vector<LatticeRow> ends;
  std::vector<int32_t> alive(n), next;
  for (size_t i = 0; i < n; ++i) alive[i] = int32_t(i);
  std::vector<uint8_t> vertex(n, 0);
  for (size_t a = 0; a < 3; ++a) {
    // Planes of constant coordinate a, rows of constant b, values along c. Only the previous
    // family's survivors take part (they keep every extreme point).
    const size_t b = (a + 1) % 3, c = (a + 2) % 3;
    const int64_t rows = hi[b] - lo[b] + 1;
    cells.assign(size_t((hi[a] - lo[a] + 1) * rows), Cell{});
    for (const int32_t i : alive) {
      const auto& p = q[size_t(i)];
      Cell& cell = cells[size_t((p[a] - lo[a]) * rows + (p[b] - lo[b]))];
      if (p[c] < cell.least) cell.least = p[c], cell.least_index = i;  // ascending i: the lowest index wins
      if (p[c] > cell.greatest) cell.greatest = p[c], cell.greatest_index = i;
    }
    for (size_t plane = 0; plane < cells.size(); plane += size_t(rows)) {
      ends.clear();
      for (int64_t r = 0; r < rows; ++r) {
        const Cell& cell = cells[plane + size_t(r)];
        if (cell.least_index >= 0) ends.push_back({r, cell.least, cell.greatest});
      }
      // The hull keeps strict vertices only, each once; back to its point through its row.
      for (const LatticePoint& v : lattice_hull_of_rows(ends)) {
        const Cell& cell = cells[plane + size_t(v.u)];
        vertex[size_t(v.v == cell.least ? cell.least_index : cell.greatest_index)] = 1;
      }
    }
    next.clear();
    for (const int32_t i : alive) {
      if (vertex[size_t(i)]) next.push_back(i), vertex[size_t(i)] = 0;
    }
    alive.swap(next);
  }
  return std::vector<int64_t>(alive.begin(), alive.end());
}

}  // namespace

static std::vector<int64_t> hull_vertex_candidates_here(const std::vector<Vec3>& points) {
  if (const std::optional<int> exponent = dyadic_lattice_exponent(points)) {
    // Dense tables pay when they are not much larger than the set.
    const int64_t max_cells = 8 * int64_t(points.size()) + (int64_t(1) << 16);
    if (auto kept = lattice_candidates(points, *exponent, max_cells)) return std::move(*kept);
  }
  std::vector<int64_t> alive(points.size());
  for (size_t p = 0; p < points.size(); ++p) alive[p] = int64_t(p);
  // In general position (a smoothed or resampled mesh) every plane holds one point: three full
  // sorts would drop nothing. A sample of 1024 evenly spaced points tells: if most of their x
  // coordinates are distinct, keep every point (a valid shortlist) and skip the sorts.
  const size_t step = std::max<size_t>(1, points.size() / 1024);
  std::vector<double> sample;
  for (size_t p = 0; p < points.size(); p += step) sample.push_back(points[p][0]);
  std::sort(sample.begin(), sample.end());
  if (size_t(std::unique(sample.begin(), sample.end()) - sample.begin()) * 2 > sample.size() && sample.size() >= 64) {
    return alive;
  }
  // The survivors of each family go on to the next: a point that is not extreme among the
  // survivors is not extreme in the whole set either (the survivors keep every extreme point).
  std::vector<char> vertex(points.size(), 0);
  std::vector<Item> items, buffer;
  std::vector<End> ends, chain;
  for (int family = 0; family < 3; ++family) {
    // Family 0: planes of constant x (rows of constant y); 1: constant y (rows z); 2: constant z (rows x).
    const int a = family, b = (family + 1) % 3, c = (family + 2) % 3;
    items.clear();
    for (const int64_t i : alive) {
      const Vec3& p = points[size_t(i)];
      items.push_back({key_of(p[a]), key_of(p[b]), key_of(p[c]), i});
    }
    // Stable from ascending indices: duplicates keep their lowest index.
    radix_sort(items, buffer);
    const size_t n = items.size();
    auto end_of = [&](const Item& it) {
      const Vec3& p = points[size_t(it.index)];
      return End{p[b], p[c], it.index};
    };
    for (size_t s = 0; s < n;) {
      size_t e = s;
      ends.clear();
      while (e < n && items[e].a == items[s].a) {
        // One row: its first and last distinct points (a middle one lies between them).
        size_t r = e;
        while (r < n && items[r].a == items[e].a && items[r].b == items[e].b) ++r;
        ends.push_back(end_of(items[e]));
        size_t last = r - 1;
        while (last > e && items[last - 1].c == items[last].c) --last;  // lowest index of the duplicates
        if (items[last].c != items[e].c) ends.push_back(end_of(items[last]));
        e = r;
      }
      mark_plane_hull(ends, chain, vertex);
      s = e;
    }
    alive.erase(std::remove_if(alive.begin(), alive.end(), [&](int64_t i) { return !vertex[size_t(i)]; }), alive.end());
    for (const int64_t i : alive) vertex[size_t(i)] = 0;
  }
  return alive;
}

// Compiled for the CPU it runs on (core/base/cpu_dispatch.h).
std::vector<int64_t> hull_vertex_candidates(const std::vector<Vec3>& points) {
  return cpu_dispatch([&] { return hull_vertex_candidates_here(points); });
}

}  // namespace soiq
