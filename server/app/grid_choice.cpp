#include "server/app/grid_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/voxelize/grid_around.h"
#include "server/app/modality_names.h"

namespace soiq::server {
namespace {}  // namespace

Result<db::SeriesRecord> find_series(const std::string& ref, const std::vector<db::SeriesRecord>& study_series,
                                     const std::string& study_uid) {
  for (const auto& s : study_series) {
    if (s.series_uid == ref) return s;
  }
  std::vector<const db::SeriesRecord*> by_modality;
  for (const auto& s : study_series) {
    if (same_modality(s.modality, ref)) by_modality.push_back(&s);
  }
  if (by_modality.size() == 1) return *by_modality[0];
  if (by_modality.size() > 1)
    return failed_precondition("study " + study_uid + " has " + std::to_string(by_modality.size()) + " " + ref +
                               " series; name one by its series uid");
  return not_found("no image series '" + ref + "' in study " + study_uid + " (by uid or modality; upload one)");
}

Result<ResolvedGrid> resolve_grid(const GridChoice& choice, const db::StructureRecord& structure,
                                  const std::vector<db::SeriesRecord>& study_series, double min_margin_mm,
                                  int64_t max_voxels) {
  ResolvedGrid out;
  if (choice.kind == GridChoice::Kind::kAxisAligned) {
    const auto& b = structure.surface.bounds_mm;
    int margin = choice.margin_voxels;
    for (double s : choice.spacing_mm) margin = std::max(margin, int(std::ceil(min_margin_mm / s)) + 1);
    SOIQ_ASSIGN_OR_RETURN(out.geometry,
                          grid_around_box({b[0], b[1], b[2]}, {b[3], b[4], b[5]}, choice.spacing_mm, margin));
    // The grid's voxel centres are multiples of the spacing whatever the margin (grid_around_box), so
    // a wider margin only adds voxels outside the surface's box: nothing inside, and every region
    // asked fits either way (the margin grew for it). The values are the same, and so is the key:
    // a query with a shell reads what precompute and narrower queries stored. (The margin is at
    // least one voxel here, so the mask's marching-cubes surface never meets the grid's border.)
    char key[160];
    std::snprintf(key, sizeof key, "axis:%.17g,%.17g,%.17g", choice.spacing_mm[0], choice.spacing_mm[1],
                  choice.spacing_mm[2]);
    out.key = key;
  } else {
    SOIQ_ASSIGN_OR_RETURN(db::SeriesRecord s, find_series(choice.series, study_series, structure.study_uid));
    out.geometry = s.geometry;
    out.key = "series:" + s.sha256;
  }
  SOIQ_RETURN_IF_ERROR(check_grid_size(out.geometry, max_voxels));
  return out;
}

}  // namespace soiq::server
