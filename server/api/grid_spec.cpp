#include "server/api/grid_spec.h"

#include "server/app/modality_names.h"

namespace soiq::server {

Result<GridChoice> grid_choice(const v1::GridSpec& spec) {
  GridChoice c;
  if (spec.margin_voxels() < 0 || spec.margin_voxels() > 1000)
    return invalid_argument("grid margin must be in [0, 1000] voxels");
  if (spec.margin_voxels() > 0) c.margin_voxels = spec.margin_voxels();
  switch (spec.target_case()) {
    case v1::GridSpec::kSeriesUid:
      c.kind = GridChoice::Kind::kSeriesUid;
      c.series = spec.series_uid();
      if (c.series.empty()) return invalid_argument("grid series_uid is empty");
      return c;
    case v1::GridSpec::kSpacingMm:
      c.spacing_mm = {spec.spacing_mm(), spec.spacing_mm(), spec.spacing_mm()};
      break;
    case v1::GridSpec::kSpacingXyz:
      c.spacing_mm = {spec.spacing_xyz().x(), spec.spacing_xyz().y(), spec.spacing_xyz().z()};
      break;
    case v1::GridSpec::TARGET_NOT_SET:
      if (!spec.series_modality().empty()) {
        c.kind = GridChoice::Kind::kSeriesModality;
        c.series = dicom_modality(spec.series_modality());
      }
      return c;
  }
  for (double s : c.spacing_mm) {
    if (!(s >= 0.01 && s <= 100)) return invalid_argument("grid spacing must be in [0.01, 100] mm");
  }
  return c;
}

}  // namespace soiq::server
