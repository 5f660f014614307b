#include "dicom/convert_rt_struct.h"

#include "dicom/volume_surface.h"

namespace soiq::dicom {
Result<ConvertedStructureSet> convert_rt_struct(const RtStructureSet& rs, const ImageGeometry& grid,
                                                int64_t max_voxels) {
  ConvertedStructureSet out;
  for (const RtRoi& roi : rs.rois) {
    if (roi.contours.empty()) {
      out.skipped.push_back(
          {roi.number, roi.name,
           roi.other_contours > 0 ? "only " + roi.other_types + " contours, no CLOSED_PLANAR" : "no contours"});
      continue;
    }
    auto fill = fill_contours(roi.contours, grid, FillRule::kEvenOdd, 0.45, max_voxels);
    // A contour the rules refuse leaves out its ROI only: the others of the set are sound.
    if (fill.status().code() == StatusCode::kInvalidArgument) {
      out.skipped.push_back({roi.number, roi.name, "refused: " + fill.status().message()});
      continue;
    }
    if (!fill.ok())
      return Status(fill.status().code(), "'" + rs.path + "' ROI " + std::to_string(roi.number) + " '" + roi.name +
                                              "': " + fill.status().message());
    ImportedStructure s;
    s.roi_number = roi.number;
    s.name = roi.name;
    s.contour_count = static_cast<int64_t>(roi.contours.size());
    s.contours_outside_grid = fill->contours_outside_grid;
    s.contours_superseded = fill->contours_superseded;
    s.volume = std::move(fill->volume);
    SOIQ_ASSIGN_OR_RETURN(s.surface, volume_surface(s.volume));
    out.structures.push_back(std::move(s));
  }
  return out;
}

}  // namespace soiq::dicom
