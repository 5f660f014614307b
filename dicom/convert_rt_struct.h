#pragma once
// RT Structure Set ROIs -> volume and surface models on the referenced series' grid (docs/DESIGN.md
// "The 1D method, precisely", step 7: planar contours go straight to the line filler).
//
// Inputs   rs: from read_rt_struct; grid: the geometry of the referenced image series
//          (read_image_series), any orientation (oblique series included: contours are mapped
//          into its continuous index space by core/voxelize/fill_contours).
// Output   One ImportedStructure per ROI with at least one CLOSED_PLANAR contour, in file order:
//          volume = core/voxelize/fill_contours with the even-odd rule (a voxel is inside iff its centre
//          is inside an odd number of the ROI's contours on its slice: holes and inner contours
//          subtract whatever their orientation, keyhole contours keep their hole);
//          surface = core/io marching_cubes of that volume (cropped to its bounding box, which
//          does not change the surface), in LPS mm; contours_outside_grid counts contours on
//          planes the grid does not have. ROIs without CLOSED_PLANAR contours (none at all, or
//          only POINT and other types) are listed in `skipped` with the reason, not converted; so
//          is an ROI a contour rule of fill_contours refuses (a contour not planar, or too far
//          from every image plane: the reason names the contour and the distance in mm), and only
//          that ROI.
// Errors   INVALID_ARGUMENT for an invalid grid; RESOURCE_EXHAUSTED over max_voxels.
// Cost     O(points + crossings + lines) per ROI plus marching cubes over its bounding box.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "dicom/read_rt_struct.h"

namespace soiq::dicom {

struct ImportedStructure {
  int64_t roi_number = 0;
  std::string name;
  int64_t contour_count = 0;
  int64_t contours_outside_grid = 0;
  int64_t contours_superseded = 0;  // fill_contours: another plane's contours were nearer their slice
  RunLengthVolume volume;           // on the referenced series' grid
  TriangleMesh surface;             // LPS mm, closed, outward; empty when the volume is
};

struct SkippedRoi {
  int64_t roi_number = 0;
  std::string name;
  std::string reason;  // "no contours", "only POINT contours"
};

struct ConvertedStructureSet {
  std::vector<ImportedStructure> structures;
  std::vector<SkippedRoi> skipped;
};

Result<ConvertedStructureSet> convert_rt_struct(const RtStructureSet& rs, const ImageGeometry& grid,
                                                int64_t max_voxels = kDefaultMaxVoxels);

}  // namespace soiq::dicom
