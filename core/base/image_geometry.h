#pragma once
// The sampling grid of an image, exactly as a DICOM series or an ITK image defines it
// (docs/DESIGN.md, "Coordinates and grids"): voxel (i,j,k) has its centre at
//   p(i,j,k) = origin + D * diag(spacing) * (i,j,k)      (LPS, mm)
// where the columns of the direction matrix D are the unit axis directions in LPS.
// Voxel data is stored with i fastest: index = i + nx * (j + ny * k).
//
// i and j (rows and columns of a slice) are orthonormal. k is either along their normal, or, for
// a series acquired with gantry tilt, a unit vector leaning away from it: the grid is then
// sheared, its slices still the planes k = const but each one shifted in-plane from the last.
// Everything here holds for both; the sheared one is kept as it is, never resampled, so that its
// voxel centres are the series' own.
//
// The slices of an unevenly spaced series are not k x spacing apart: slice_positions_mm holds
// where each one lies along k's axis, and the grid is affine between consecutive slices only. Its
// "lattice" coordinates (i, j, z) are those of the affine grid of spacing_mm: slice k lies on the
// plane z = lattice_z(k) = slice_positions_mm[k] / spacing_mm[2], not at z = k. For every evenly
// spaced grid the lattice is the index space.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "core/base/vec3.h"

namespace soiq {

struct ImageGeometry {
  Vec3 origin_mm{0, 0, 0};               // centre of voxel (0,0,0), LPS
  Vec3 spacing_mm{1, 1, 1};              // along i, j, k; > 0
  std::array<int64_t, 3> dims{0, 0, 0};  // nx, ny, nz; >= 0
  Mat3 direction = identity3();          // columns: unit directions of i, j, k in LPS
  // Unevenly spaced series only: the position of each slice along k's axis in mm from slice 0
  // (0 first, strictly increasing, dims[2] of them); spacing_mm[2] is then their mean step. Empty
  // for every evenly spaced grid.
  std::vector<double> slice_positions_mm;

  int64_t voxel_count() const { return dims[0] * dims[1] * dims[2]; }
  // True when k leans away from the normal i x j by more than validate_geometry's orthonormality
  // tolerance (1e-4): a sheared (gantry-tilted) grid. Grids that are not take the orthonormal
  // formulas below, bit for bit what they always were.
  bool sheared() const;
  // The distance between consecutive slice planes along their normal: spacing_mm[2] unless sheared,
  // spacing_mm[2] x cos(tilt) when it is.
  double slice_distance_mm() const;
  // The volume of one voxel, a parallelepiped when sheared: spacing x, y and slice_distance_mm().
  // On an unevenly spaced grid, that of a mean slice: voxel_volume_mm3(k) is slice k's.
  double voxel_volume_mm3() const;
  bool uneven() const { return !slice_positions_mm.empty(); }
  // Slice k's voxel volume: its thickness reaches halfway to each neighbour (the end slices as far
  // outwards as inwards). voxel_volume_mm3() for every k when the grid is evenly spaced.
  double voxel_volume_mm3(int64_t k) const;
  // Continuous slice index k -> lattice z, and back: linear between slices, and beyond the ends
  // along the end steps. Identities unless uneven.
  double lattice_z(double k) const;
  double slice_index(double z) const;
  // The affine part: lattice (i, j, z) <-> LPS. The index maps below for evenly spaced grids.
  Vec3 lattice_to_physical(const Vec3& ijz) const;
  Vec3 physical_to_lattice(const Vec3& p_mm) const;
  // The orthonormal frame of the slices, columns (i, j, normal), the normal on k's side of the
  // planes: the direction matrix itself unless sheared.
  Mat3 frame() const;
  // The tilt: the angle between k and the normal of the slices, in degrees (0 unless sheared).
  double tilt_degrees() const;
  // Continuous index (i,j,k) -> LPS point.
  Vec3 index_to_physical(const Vec3& ijk) const;
  // LPS point -> continuous index; voxel centres sit at integers. Needs a valid geometry.
  Vec3 physical_to_index(const Vec3& p_mm) const;
  bool operator==(const ImageGeometry&) const = default;
};

// OK when spacing is finite and > 0, dims >= 0, values finite, i and j orthonormal and k a unit
// vector (to 1e-4, as DICOM orientation vectors are often stored with 6 decimals) either
// perpendicular to both (to 1e-4) or leaning at most kMaxTiltDegrees from their normal, and slice
// positions, if any, one per slice (at least 3), finite, 0 first, each step > 0 and spacing_mm[2]
// their mean step (to 1e-9 relative). INVALID_ARGUMENT naming the offending field otherwise.
Status validate_geometry(const ImageGeometry& g);

// Gantry tilts reach 30 degrees; beyond 60 a "slice stack" is no longer one.
inline constexpr double kMaxTiltDegrees = 60;

// RESOURCE_EXHAUSTED when the grid has more voxels than `max_voxels`, with a message that says how
// many it has and what to do; checked before anything of that size is allocated.
Status check_grid_size(const ImageGeometry& g, int64_t max_voxels);

// The default ceiling for grids soiq materialises (1e9 voxels = 1 GB as uint8).
inline constexpr int64_t kDefaultMaxVoxels = 1'000'000'000;

// OK when a and b sample the same voxel centres: equal dims, and origin, spacing and direction equal
// to within what file formats keep (NIfTI stores its geometry in float32): 1e-4 mm for the origin,
// 1e-6 relative for the spacing, 1e-5 for direction cosines. INVALID_ARGUMENT saying what differs.
Status check_same_grid(const ImageGeometry& a, const ImageGeometry& b);

// "107x107x107 voxels of 1x1x1 mm"
std::string describe(const ImageGeometry& g);

// The part of `g` of `dims` voxels from voxel `lo` (a crop): the same voxel centres, voxel
// lo + (i,j,k) of `g` at (i,j,k). An unevenly spaced grid keeps its slices' positions from slice
// lo[2] on, or becomes evenly spaced when the part holds fewer than 3 slices. Beyond the part's
// outermost slices the two extend differently unless those are `g`'s own end slices: a caller
// that reads past them (marching cubes' padding) keeps one more slice of `g` on each side.
ImageGeometry sub_grid(const ImageGeometry& g, const std::array<int64_t, 3>& lo, const std::array<int64_t, 3>& dims);

}  // namespace soiq
