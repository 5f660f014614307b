#include "core/base/coverage_volume.h"

#include <algorithm>
#include <cmath>

namespace soiq {

namespace coverage_volume_detail {

// Appends [begin, end) to the runs of the current line (those from `line_first`), merging it with
// the previous run when they touch, so the result stays canonical.
void append_run(std::vector<Run>& runs, int64_t line_first, int32_t begin, int32_t end) {
  if (int64_t(runs.size()) > line_first && runs.back().end == begin) {
    runs.back().end = end;
    return;
  }
  runs.push_back({begin, end});
}

// The runs of the voxels whose fraction passes `keep` (full runs always pass).
template <typename Keep>
RunLengthVolume runs_where(const CoverageVolume& v, Keep keep) {
  RunLengthVolume out;
  out.geometry = v.geometry;
  const int64_t lines = v.line_count();
  out.line_start.resize(size_t(lines + 1));
  for (int64_t l = 0; l < lines; ++l) {
    const int64_t first = int64_t(out.runs.size());
    out.line_start[size_t(l)] = first;
    int64_t r = v.full_start[size_t(l)], p = v.partial_start[size_t(l)];
    const int64_t r_end = v.full_start[size_t(l + 1)], p_end = v.partial_start[size_t(l + 1)];
    // The two lists are each sorted and never overlap: merge them by position.
    while (r < r_end || p < p_end) {
      if (p == p_end || (r < r_end && v.full[size_t(r)].begin < v.partial[size_t(p)].i)) {
        append_run(out.runs, first, v.full[size_t(r)].begin, v.full[size_t(r)].end);
        ++r;
      } else {
        const PartialVoxel& pv = v.partial[size_t(p++)];
        if (keep(pv.fraction)) append_run(out.runs, first, pv.i, pv.i + 1);
      }
    }
  }
  out.line_start[size_t(lines)] = int64_t(out.runs.size());
  return out;
}

// Writes each voxel's value into a dense array: `full` for wholly covered, value(f) for partial.
template <typename T, typename Value>
void fill_values(const CoverageVolume& v, T* out, T full, Value value) {
  const int64_t nx = v.geometry.dims[0];
  for (int64_t l = 0; l < v.line_count(); ++l) {
    T* row = out + l * nx;
    for (int64_t r = v.full_start[size_t(l)]; r < v.full_start[size_t(l + 1)]; ++r) {
      std::fill(row + v.full[size_t(r)].begin, row + v.full[size_t(r)].end, full);
    }
    for (int64_t p = v.partial_start[size_t(l)]; p < v.partial_start[size_t(l + 1)]; ++p) {
      row[v.partial[size_t(p)].i] = value(v.partial[size_t(p)].fraction);
    }
  }
}

}  // namespace coverage_volume_detail

double covered_voxels(const CoverageVolume& v) {
  double sum = 0;
  for (const Run& r : v.full) sum += double(r.end - r.begin);
  for (const PartialVoxel& p : v.partial) sum += double(p.fraction);
  return sum;
}

RunLengthVolume threshold(const CoverageVolume& v, double threshold) {
  return coverage_volume_detail::runs_where(v, [threshold](float f) { return double(f) >= threshold; });
}

RunLengthVolume wholly_covered(const CoverageVolume& v) {
  return coverage_volume_detail::runs_where(v, [](float) { return false; });
}

RunLengthVolume any_coverage(const CoverageVolume& v) {
  return coverage_volume_detail::runs_where(v, [](float) { return true; });
}

Result<Image> to_fraction_image(const CoverageVolume& v, int64_t max_voxels) {
  SOIQ_RETURN_IF_ERROR(check_grid_size(v.geometry, max_voxels));
  Image image;
  image.geometry = v.geometry;
  image.voxels.assign(size_t(v.geometry.voxel_count()), 0.f);
  coverage_volume_detail::fill_values(v, image.voxels.data(), 1.f, [](float f) { return f; });
  return image;
}

Result<Mask> to_fraction_bytes(const CoverageVolume& v, int64_t max_voxels) {
  SOIQ_RETURN_IF_ERROR(check_grid_size(v.geometry, max_voxels));
  Mask bytes;
  bytes.geometry = v.geometry;
  bytes.voxels.assign(size_t(v.geometry.voxel_count()), 0);
  coverage_volume_detail::fill_values(v, bytes.voxels.data(), uint8_t(255), fraction_byte);
  return bytes;
}

uint8_t fraction_byte(float f) { return uint8_t(std::clamp(std::lround(255.0 * double(f)), 1L, 254L)); }

int64_t coverage_bytes(const CoverageVolume& v) {
  return int64_t((v.full_start.capacity() + v.partial_start.capacity()) * sizeof(int64_t) +
                 v.full.capacity() * sizeof(Run) + v.partial.capacity() * sizeof(PartialVoxel));
}

}  // namespace soiq
