#include "core/base/run_length_volume.h"

#include <algorithm>
#include <cstring>

#include "core/base/parallel_for.h"

namespace soiq {

RunLengthVolume empty_volume(const ImageGeometry& g) {
  RunLengthVolume v;
  v.geometry = g;
  v.line_start.assign(size_t(g.dims[1] * g.dims[2] + 1), 0);
  return v;
}

int64_t voxel_count(const RunLengthVolume& v) {
  int64_t n = 0;
  for (const Run& r : v.runs) n += r.end - r.begin;
  return n;
}

int64_t run_length_bytes(const RunLengthVolume& v) {
  return int64_t(v.line_start.capacity() * sizeof(int64_t) + v.runs.capacity() * sizeof(Run));
}

void fill_dense(const RunLengthVolume& v, uint8_t* out) {
  const int64_t nx = v.geometry.dims[0];
  const int64_t lines = v.line_count();
  for (int64_t l = 0; l < lines; ++l) {
    uint8_t* row = out + l * nx;
    for (int64_t r = v.line_start[l]; r < v.line_start[l + 1]; ++r) {
      std::memset(row + v.runs[r].begin, 1, size_t(v.runs[r].end - v.runs[r].begin));
    }
  }
}

VoxelBox voxel_box(const RunLengthVolume& v) {
  VoxelBox b;
  const int64_t ny = v.geometry.dims[1];
  for (int64_t l = 0; l < v.line_count(); ++l) {
    const int64_t first = v.line_start[size_t(l)], last = v.line_start[size_t(l) + 1];
    if (first == last) continue;
    const std::array<int64_t, 3> lo{v.runs[size_t(first)].begin, l % ny, l / ny};
    const std::array<int64_t, 3> hi{v.runs[size_t(last) - 1].end - 1, l % ny, l / ny};
    for (size_t a = 0; a < 3; ++a) {
      b.lo[a] = b.empty ? lo[a] : std::min(b.lo[a], lo[a]);
      b.hi[a] = b.empty ? hi[a] : std::max(b.hi[a], hi[a]);
    }
    b.empty = false;
  }
  return b;
}

std::vector<uint8_t> box_mask(const RunLengthVolume& v, const VoxelBox& box) {
  const std::array<int64_t, 3> n = box.dims();
  std::vector<uint8_t> out(size_t(std::max<int64_t>(n[0], 0) * std::max<int64_t>(n[1], 0) * std::max<int64_t>(n[2], 0)),
                           0);
  const auto& d = v.geometry.dims;
  for (int64_t k = std::max<int64_t>(box.lo[2], 0); k <= std::min(box.hi[2], d[2] - 1); ++k) {
    for (int64_t j = std::max<int64_t>(box.lo[1], 0); j <= std::min(box.hi[1], d[1] - 1); ++j) {
      const int64_t l = j + d[1] * k;
      uint8_t* row = out.data() + n[0] * ((j - box.lo[1]) + n[1] * (k - box.lo[2]));
      for (int64_t r = v.line_start[size_t(l)]; r < v.line_start[size_t(l) + 1]; ++r) {
        const int64_t b = std::max<int64_t>(v.runs[size_t(r)].begin, box.lo[0]);
        const int64_t e = std::min<int64_t>(v.runs[size_t(r)].end, box.hi[0] + 1);
        if (b < e) std::memset(row + (b - box.lo[0]), 1, size_t(e - b));
      }
    }
  }
  return out;
}

Result<Mask> to_mask(const RunLengthVolume& v, int64_t max_voxels, int threads) {
  SOIQ_RETURN_IF_ERROR(check_grid_size(v.geometry, max_voxels));
  Mask m;
  m.geometry = v.geometry;
  m.voxels.assign(size_t(v.geometry.voxel_count()), 0);
  const int64_t nx = v.geometry.dims[0];
  parallel_for(
      v.line_count(), threads,
      [&](int64_t first, int64_t last) {
        uint8_t* out = m.voxels.data();
        for (int64_t l = first; l < last; ++l) {
          for (int64_t r = v.line_start[size_t(l)]; r < v.line_start[size_t(l + 1)]; ++r) {
            std::memset(out + l * nx + v.runs[size_t(r)].begin, 1,
                        size_t(v.runs[size_t(r)].end - v.runs[size_t(r)].begin));
          }
        }
      },
      256);
  return m;
}

RunLengthVolume from_mask(const Mask& m) {
  RunLengthVolume v;
  v.geometry = m.geometry;
  const int64_t nx = m.geometry.dims[0];
  const int64_t lines = m.geometry.dims[1] * m.geometry.dims[2];
  v.line_start.resize(size_t(lines + 1));
  for (int64_t l = 0; l < lines; ++l) {
    v.line_start[l] = int64_t(v.runs.size());
    const uint8_t* row = m.voxels.data() + l * nx;
    int64_t i = 0;
    while (i < nx) {
      while (i < nx && row[i] == 0) ++i;
      if (i == nx) break;
      const int64_t begin = i;
      while (i < nx && row[i] != 0) ++i;
      v.runs.push_back({int32_t(begin), int32_t(i)});
    }
  }
  v.line_start[lines] = int64_t(v.runs.size());
  return v;
}

double VolumeComparison::iou() const {
  const int64_t uni = count_a + count_b - intersection;
  return uni == 0 ? 1.0 : double(intersection) / double(uni);
}

double VolumeComparison::dice() const {
  const int64_t sum = count_a + count_b;
  return sum == 0 ? 1.0 : 2.0 * double(intersection) / double(sum);
}

namespace {

// |A ∩ B| of two sorted disjoint run lists (a merge walk).
int64_t intersect_runs(const Run* a, const Run* a_end, const Run* b, const Run* b_end) {
  int64_t n = 0;
  while (a != a_end && b != b_end) {
    const int32_t lo = std::max(a->begin, b->begin);
    const int32_t hi = std::min(a->end, b->end);
    if (hi > lo) n += hi - lo;
    if (a->end < b->end)
      ++a;
    else
      ++b;
  }
  return n;
}

}  // namespace

Result<VolumeComparison> compare(const RunLengthVolume& a, const RunLengthVolume& b) {
  if (Status same = check_same_grid(a.geometry, b.geometry); !same.ok()) {
    return invalid_argument("cannot compare volumes on different grids: " + same.message());
  }
  VolumeComparison c;
  c.count_a = voxel_count(a);
  c.count_b = voxel_count(b);
  for (int64_t l = 0; l < a.line_count(); ++l) {
    c.intersection += intersect_runs(a.runs.data() + a.line_start[l], a.runs.data() + a.line_start[l + 1],
                                     b.runs.data() + b.line_start[l], b.runs.data() + b.line_start[l + 1]);
  }
  c.only_a = c.count_a - c.intersection;
  c.only_b = c.count_b - c.intersection;
  return c;
}

}  // namespace soiq
