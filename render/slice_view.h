#pragma once
// How one plane of a grid is shown on a screen, the way radiology viewers show it: axial with the
// patient's anterior up and right on the screen's left, coronal with superior up and right on the
// left, sagittal with superior up and anterior on the left. The grid's voxel axes are matched one
// to one with the patient's axes from the direction cosines (never assumed axis-aligned): of the
// six matchings, the one with the largest sum of |cosine|, since matching each voxel axis to its
// own largest component can give two axes one patient axis even on an orthonormal grid. An axis is
// flipped when it runs against the screen's direction. The letters at the four edges name where the
// screen's directions point in the patient, from the same cosines: the components over 1e-3 in
// magnitude, largest first (one letter for an axis-aligned grid, "LA", "SLP" for an oblique one).
//
// Slices are numbered along the plane's normal voxel axis as the grid stores them (k = 0..n-1 for
// an axial plane of an axial series), so a slice number means the same as in the grid.
//
// Errors   INVALID_ARGUMENT for an unknown plane name, a slice out of range, or an image or volume
//          not on the grid `axes` was made from (naming both sizes); FAILED_PRECONDITION from
//          slice_axes when the geometry is invalid (validate_geometry: a direction that is not
//          orthonormal, a spacing <= 0), as no matching of its axes then means anything.
// Cost     slice_axes O(1); image_slice and mask_slice O(width x height) and O(runs on the slice).

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/image.h"
#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"

namespace soiq::render {

enum class Plane { kAxial, kCoronal, kSagittal };

// "axial", "coronal", "sagittal". INVALID_ARGUMENT listing them otherwise.
Result<Plane> plane_of_name(const std::string& name);
const char* plane_name(Plane plane);

struct SliceAxes {
  Plane plane = Plane::kAxial;
  int normal_axis = 2;                   // voxel axis (0 i, 1 j, 2 k) the slices are numbered along
  int across_axis = 0;                   // voxel axis shown left to right
  int down_axis = 1;                     // voxel axis shown top to bottom
  bool flip_across = false;              // index decreases from the screen's left to its right
  bool flip_down = false;                // index decreases from the screen's top to its bottom
  int64_t slice_count = 0;               // along normal_axis
  int64_t width = 0, height = 0;         // pixels of a slice: dims[across_axis], dims[down_axis]
  double pixel_width_mm = 1;             // spacing along across_axis
  double pixel_height_mm = 1;            // spacing along down_axis
  std::string left, right, top, bottom;  // orientation letters at the screen's edges
};

Result<SliceAxes> slice_axes(const ImageGeometry& geometry, Plane plane);

// Slice `k` as shown: row-major from the screen's top-left pixel, width x height values.
struct SliceImage {
  int64_t width = 0, height = 0;
  std::vector<float> values;
};
struct SliceMask {
  int64_t width = 0, height = 0;
  std::vector<uint8_t> inside;  // 1 inside, 0 outside
};

// `image` and `volume` are on the geometry `axes` was made from. INVALID_ARGUMENT when k is not in
// 0..slice_count-1 or the voxel count differs from the geometry's.
Result<SliceImage> image_slice(const Image& image, const SliceAxes& axes, int64_t k);
Result<SliceMask> mask_slice(const RunLengthVolume& volume, const SliceAxes& axes, int64_t k);

// Inside voxels per slice along axes.normal_axis (slice_count entries): which slices hold the
// structure (a montage), and the largest one (--through largest). O(runs).
std::vector<int64_t> inside_per_slice(const RunLengthVolume& volume, const SliceAxes& axes);

}  // namespace soiq::render
