#include "core/hull_vertex_candidates.h"

#include <algorithm>
#include <cstring>

#include "core/exact_predicates.h"

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

}  // namespace

std::vector<int64_t> hull_vertex_candidates(const std::vector<Vec3>& points) {
  // The survivors of each family go on to the next: a point that is not extreme among the
  // survivors is not extreme in the whole set either (the survivors keep every extreme point).
  std::vector<int64_t> alive(points.size());
  for (size_t p = 0; p < points.size(); ++p) alive[p] = int64_t(p);
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

}  // namespace soiq
