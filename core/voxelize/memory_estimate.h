#pragma once
// How many bytes a conversion or a feature computation will hold at its peak, known before any of
// it is allocated, so that a server can admit work by bytes (not by count) and refuse at once what
// can never fit. A 96 KB mesh whose thin box spans 12 m turns into 1.4e8 row lines and ~16 GB of
// crossings: the grid's voxel count alone does not tell that, the lines and crossings do.
//
// conversion_peak_bytes   voxelize_1d on `geometry`: per row line (ny x nz of them) its reserved
//                         crossings, line index and sort counts (~120 bytes: the crossing buffer
//                         reserves four crossings of 24 bytes per line); per crossing beyond that
//                         reserve 48 bytes (buffer growth doubles); per run 16 bytes; the mesh in
//                         index space; robust mode's dense 2-of-3 votes (2 bytes per voxel).
//                         Crossings are bounded from the surface's area and perimeter (its
//                         SurfaceMeasure, computed once per surface): a triangle is crossed by the
//                         row lines through its (y,z) projection in index space, at most its
//                         projected area plus half its perimeter plus one (Pick), and a projection
//                         is never larger than the triangle, whatever the grid's orientation.
// features_extra_bytes    what structure_features adds on top of the runs: mask-surface sweep and
//                         hulls (~64 bytes per run), ~0.5 byte per grid voxel measured (1 counted),
//                         the decoded images not yet cached (4 bytes per voxel) and the
//                         intensities gathered per region (4 bytes per grid voxel at most).
// coverage_peak_bytes     coverage_1d with n x n lines per voxel: the crossings bound above with
//                         n^2 times the area term and n times the perimeter term, each crossing
//                         held once by one of the threads' slice buffers (64 bytes: found, with
//                         growth, then grouped by line); one slice's line index per thread;
//                         runs (<= half the crossings, kept twice: the slice's and the result's);
//                         partly covered voxels (8 bytes, twice), of which there are no more than
//                         the voxels the surface touches: each lies within a voxel diagonal d of
//                         it, so at most (2 d A + pi d^2 P + 4/3 pi d^3 T) / voxel volume, and never
//                         more than the grid.
// fraction_export_extra_bytes dense fractions of `bytes_per_voxel` (1 or 4) and their
//                         compressed NIfTI (2 x bytes per voxel + 1 counted).
// mask_export_extra_bytes a dense mask and its compressed NIfTI (measured 2 bytes per voxel; 3
//                         counted).
// Calibrated on measured peaks (VmHWM) of `soiq features`/`soiq convert`: the estimate is above
// the measured peak for a thin 12 m box (15.6 GB measured), a 100 mm sphere at 1, 0.5 and 0.3 mm,
// and a 12 m long bar; see tests/core/memory_estimate_test.cpp.
// Cost surface_measure O(triangles), once per surface; the estimates O(1); thread-safe. Results
// saturate at INT64_MAX rather than overflow.

#include <cstdint>
#include <string>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

struct ConversionEstimate {
  int64_t lines = 0;      // row lines of the grid (ny x nz)
  int64_t crossings = 0;  // upper bound of the surface's crossings with them
  int64_t bytes = 0;      // peak bytes of voxelize_1d
};

// What the estimate needs of a surface, independent of the grid.
struct SurfaceMeasure {
  int64_t vertices = 0;
  int64_t triangles = 0;
  double area_mm2 = 0;      // an upper bound (L1 norms)
  double perimeter_mm = 0;  // summed over triangles (shared edges twice); an upper bound too
};
SurfaceMeasure surface_measure(const TriangleMesh& mesh);

ConversionEstimate conversion_peak_bytes(const SurfaceMeasure& surface, const ImageGeometry& geometry, bool robust);
ConversionEstimate conversion_peak_bytes(const TriangleMesh& mesh, const ImageGeometry& geometry, bool robust);
ConversionEstimate coverage_peak_bytes(const SurfaceMeasure& surface, const ImageGeometry& geometry,
                                       int lines_per_voxel);
int64_t fraction_export_extra_bytes(const ImageGeometry& geometry, int bytes_per_voxel);
// An upper bound of the voxels with any coverage: those inside (the enclosed volume is at most
// A^(3/2) / (6 sqrt(pi)), the isoperimetric inequality, for any closed surface of area A) plus those
// the surface touches (as coverage_peak_bytes counts them), never more than the grid.
int64_t covered_voxels_bound(const SurfaceMeasure& surface, const ImageGeometry& geometry);

// Extra bytes of a feature computation over a conversion estimated as `conversion`, with
// `uncached_image_voxels` voxels of images still to decode and `regions` regions with intensities.
int64_t features_extra_bytes(const ConversionEstimate& conversion, const ImageGeometry& geometry,
                             int64_t uncached_image_voxels, int regions);

int64_t mask_export_extra_bytes(const ImageGeometry& geometry);

// The default memory budget: half of the memory this process may use: the least of the machine's
// RAM, the cgroup's memory.max (a container's limit), and what is left of the process's
// RLIMIT_AS and RLIMIT_DATA (ulimit -v, -d) past its present use and its threads' future stacks
// and arenas (1.1 GiB). At least 64 MiB.
int64_t default_memory_budget_bytes();

// A byte size as people write it: "8589934592", "8G", "512M", "64K", "1T" (binary multiples; a
// trailing "B" or "iB" allowed). INVALID_ARGUMENT naming `what` otherwise.
Result<int64_t> parse_byte_size(const std::string& text, const std::string& what);

// "15.6 GB", "420 MB", "12 KB": bytes for messages (decimal units, 3 significant digits).
std::string human_bytes(int64_t bytes);

}  // namespace soiq
