#pragma once
// Where a stored surface is converted (docs/DESIGN.md "Coordinates and grids"): on a stored image
// series' grid (named by uid, or by modality within the structure's study), or on an axis-aligned
// grid around the surface at a spacing with a margin. Resolving needs no decoding: the axis-aligned
// grid comes from the stored bounds (grid_around_box), so the feature cache can be consulted first.
//
// resolve_grid
//   min_margin_mm  the axis-aligned grid's margin is grown so that shells this wide fit inside it
//                  (a shell is clipped at the grid border, regions.h).
//   max_voxels     a larger grid is RESOURCE_EXHAUSTED naming its size and the limit.
//   Errors: NOT_FOUND for an unknown series or no series of that modality in the study;
//   FAILED_PRECONDITION when the study has several series of that modality (name one by uid);
//   INVALID_ARGUMENT for a bad spacing or margin.
// The returned key names the grid for the feature cache: equal keys, equal values. Two axis-aligned
// grids of one spacing that differ only in a margin of at least one voxel share a key: same voxel
// centres, same values (grid_choice.cpp says why).

#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "db/store.h"

namespace soiq::server {

// Made from a request by the api (server/api/grid_spec.h), which checks spacing and margin.
struct GridChoice {
  enum class Kind { kAxisAligned, kSeriesUid, kSeriesModality } kind = Kind::kAxisAligned;
  Vec3 spacing_mm{1, 1, 1};
  int margin_voxels = 2;
  std::string series;  // uid or modality
};

struct ResolvedGrid {
  ImageGeometry geometry;
  std::string key;
};

// A series of the study by uid or (case-insensitive) modality.
Result<db::SeriesRecord> find_series(const std::string& ref, const std::vector<db::SeriesRecord>& study_series,
                                     const std::string& study_uid);

Result<ResolvedGrid> resolve_grid(const GridChoice& choice, const db::StructureRecord& structure,
                                  const std::vector<db::SeriesRecord>& study_series, double min_margin_mm,
                                  int64_t max_voxels);

}  // namespace soiq::server
