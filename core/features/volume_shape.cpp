#include "core/features/volume_shape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/geometry/symmetric_eigenvalues.h"

namespace soiq {
namespace {

__extension__ typedef __int128 Int128;  // exact products of 64-bit sums

// sum of i^2 over the run b, ..., b + n - 1: n b^2 + b n (n - 1) + (n - 1) n (2n - 1) / 6, exact.
// The last term in 64 bits while it fits (runs shorter than 2^20 voxels: every real grid), since a
// 128-bit division is a library call.
Int128 run_sum_of_squares(int64_t b, int64_t n) {
  const Int128 head = Int128(n) * b * b + Int128(b) * (n * (n - 1));
  if (n < (int64_t(1) << 20)) return head + (n - 1) * n * (2 * n - 1) / 6;
  return head + Int128(n - 1) * n * (2 * n - 1) / 6;
}

// Index-space moments: s[a] = sum of coordinate a, ss[a][b] = sum of coordinate a times b.
struct IndexMoments {
  int64_t n = 0;
  int64_t s[3] = {0, 0, 0};
  Int128 ss[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

// One sweep over the runs: the moments of the inside voxel centres' indices and their LPS bounding
// box.
struct VolumeSweep {
  IndexMoments moments;
  Vec3 bbox_min_mm, bbox_max_mm;
  // Unevenly spaced grids only: per slice k, its voxel count and the sums of their i and j.
  std::vector<std::array<int64_t, 3>> per_slice;
};

VolumeSweep sweep_runs(const RunLengthVolume& volume) {
  const ImageGeometry& g = volume.geometry;
  VolumeSweep out;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  out.bbox_min_mm = {kInf, kInf, kInf};
  out.bbox_max_mm = {-kInf, -kInf, -kInf};
  const int64_t ny = g.dims[1], lines = volume.line_count();
  // Sums per line in plain integers, then into the 128-bit totals once per line with the line's j
  // and k: 128-bit accumulators kept in memory stall on every add (a 16-byte load of two 8-byte
  // stores cannot be forwarded), which made this loop several times slower per run.
  Int128 s00 = 0, s11 = 0, s22 = 0, s01 = 0, s02 = 0, s12 = 0;
  int64_t n_total = 0, s0 = 0, s1 = 0, s2 = 0;
  if (g.uneven()) out.per_slice.assign(size_t(g.dims[2]), {0, 0, 0});
  for (int64_t l = 0; l < lines; ++l) {
    const int64_t first = volume.line_start[l], last = volume.line_start[l + 1];
    if (first == last) continue;
    const int64_t j = l % ny, k = l / ny;
    int64_t n_line = 0, si_line = 0;  // below nx^2 / 2 < 2^62
    Int128 sii_line = 0;
    for (int64_t r = first; r < last; ++r) {
      const int64_t b = volume.runs[r].begin, e = volume.runs[r].end;
      const int64_t n = e - b;
      n_line += n;
      si_line += (b + e - 1) * n / 2;  // (b + e - 1) * n is always even
      sii_line += run_sum_of_squares(b, n);
    }
    n_total += n_line;
    s0 += si_line, s1 += n_line * j, s2 += n_line * k;
    if (!out.per_slice.empty()) {
      auto& slice = out.per_slice[size_t(k)];
      slice[0] += n_line, slice[1] += si_line, slice[2] += n_line * j;
    }
    s00 += sii_line, s11 += Int128(n_line) * j * j, s22 += Int128(n_line) * k * k;
    s01 += Int128(j) * si_line, s02 += Int128(k) * si_line, s12 += Int128(n_line) * j * k;
    // An LPS coordinate is affine in i along the line: its extremes are at the line's first and
    // last inside voxel (runs are sorted).
    for (const int64_t i : {int64_t(volume.runs[first].begin), int64_t(volume.runs[last - 1].end) - 1}) {
      const Vec3 p = g.index_to_physical({double(i), double(j), double(k)});
      for (int a = 0; a < 3; ++a) {
        out.bbox_min_mm[a] = std::min(out.bbox_min_mm[a], p[a]);
        out.bbox_max_mm[a] = std::max(out.bbox_max_mm[a], p[a]);
      }
    }
  }
  IndexMoments& m = out.moments;
  m.n = n_total;
  m.s[0] = s0, m.s[1] = s1, m.s[2] = s2;
  m.ss[0][0] = s00, m.ss[1][1] = s11, m.ss[2][2] = s22, m.ss[0][1] = s01, m.ss[0][2] = s02, m.ss[1][2] = s12;
  return out;
}

}  // namespace

Result<VolumeShape> volume_shape(const RunLengthVolume& volume, CovarianceDivisor divisor) {
  const ImageGeometry& g = volume.geometry;
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  const int64_t lines = volume.line_count();
  if (int64_t(volume.line_start.size()) != lines + 1 || volume.line_start.back() != int64_t(volume.runs.size())) {
    return invalid_argument("volume has " + std::to_string(volume.line_start.size()) + " line starts but its grid " +
                            describe(g) + " needs " + std::to_string(lines + 1));
  }
  const VolumeSweep sweep = sweep_runs(volume);
  const IndexMoments& m = sweep.moments;
  if (m.n == 0) return invalid_argument("volume on " + describe(g) + " has no inside voxel; shape is undefined");

  VolumeShape out;
  out.bbox_min_mm = sweep.bbox_min_mm;
  out.bbox_max_mm = sweep.bbox_max_mm;
  out.voxel_count = m.n;
  out.voxel_volume_mm3 = double(m.n) * g.voxel_volume_mm3();
  const double nd = double(m.n);
  out.centroid_mm = g.index_to_physical({double(m.s[0]) / nd, double(m.s[1]) / nd, double(m.s[2]) / nd});

  // Index-space covariance: (N * S_ab - S_a * S_b) / (N * divisor), the numerator exact in 128 bits.
  const double denominator = divisor == CovarianceDivisor::kN || m.n == 1 ? nd : nd - 1;
  double ci[3][3];
  for (int a = 0; a < 3; ++a) {
    for (int c = a; c < 3; ++c) {
      const Int128 num = m.n * m.ss[a][c] - Int128(m.s[a]) * m.s[c];
      ci[a][c] = ci[c][a] = double(num) / nd / denominator;
    }
  }
  if (g.uneven()) {
    // Slices are not k spacings apart: each voxel weighs its slice's volume, and the moments along
    // k are taken at the slices' lattice heights (in double: they are not integers).
    double volume_mm3 = 0, sz = 0, szz = 0, sxz = 0, syz = 0;
    for (size_t k = 0; k < sweep.per_slice.size(); ++k) {
      const auto& [n, si, sj] = sweep.per_slice[k];
      if (n == 0) continue;
      const double z = g.lattice_z(double(k));
      volume_mm3 += double(n) * g.voxel_volume_mm3(int64_t(k));
      sz += double(n) * z, szz += double(n) * z * z, sxz += double(si) * z, syz += double(sj) * z;
    }
    out.voxel_volume_mm3 = volume_mm3;
    const double mean[3] = {double(m.s[0]) / nd, double(m.s[1]) / nd, sz / nd};
    out.centroid_mm = g.lattice_to_physical({mean[0], mean[1], mean[2]});
    const double sums[3] = {sxz, syz, szz};
    for (int a = 0; a < 3; ++a) ci[a][2] = ci[2][a] = (sums[a] - nd * mean[a] * mean[2]) / denominator;
  }
  // LPS covariance A ci A^T, A = direction * diag(spacing).
  Mat3 a_mat{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a_mat[r][c] = g.direction[r][c] * g.spacing_mm[c];
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      double v = 0;
      for (int p = 0; p < 3; ++p) {
        for (int q = 0; q < 3; ++q) v += a_mat[r][p] * ci[p][q] * a_mat[c][q];
      }
      out.covariance_mm2[r][c] = v;
    }
  }
  Vec3 l = symmetric_eigenvalues(out.covariance_mm2);
  for (double& x : l) x = std::max(x, 0.0);  // a flat structure's zero eigenvalue may round below 0
  out.eigenvalues_mm2 = l;
  out.major_axis_length_mm = 4 * std::sqrt(l[0]);
  out.minor_axis_length_mm = 4 * std::sqrt(l[1]);
  out.least_axis_length_mm = 4 * std::sqrt(l[2]);
  out.elongation = std::sqrt(l[1] / l[0]);
  out.flatness = std::sqrt(l[2] / l[0]);
  return out;
}

}  // namespace soiq
