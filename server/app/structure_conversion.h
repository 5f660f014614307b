#pragma once
// A stored structure converted to a volume model on a chosen grid (docs/DESIGN.md "Coordinates and
// grids", "The 1D method, precisely"), for the Convert RPC: the grid resolved from the structure's study, the
// work admitted against the memory budget and run on the worker pool, and the volume handed back
// with its reservation, since the runs (and a mask made from them) live until the caller has sent
// them.
//
// Inputs   structure_id: a stored structure. choice: its grid (server/app/grid_choice.h).
//          fill_rule: nonzero or even-odd. mask_export: whether the caller will make a dense mask
//          of it (mask_nifti_bytes), which the admission counts. stop: CANCELLED or
//          DEADLINE_EXCEEDED once the caller is gone (checked while waiting for the budget).
// Output   The structure, its grid, the runs, the mesh defects, and the held reservation.
// Errors   NOT_FOUND for an unknown structure or grid series; resolve_grid's errors;
//          RESOURCE_EXHAUSTED for a grid over the voxel limit or work that can never fit the
//          budget; FeatureEngine::convert's errors (DATA_LOSS for a damaged blob).

#include <cstdint>
#include <functional>
#include <string>

#include "core/base/coverage_volume.h"
#include "core/base/fill_rule.h"
#include "core/base/status.h"
#include "core/voxelize/voxelize_1d.h"
#include "db/store.h"
#include "server/app/feature_engine.h"
#include "server/app/grid_choice.h"
#include "server/app/memory_budget.h"
#include "server/util/worker_pool.h"

namespace soiq::server {

struct StructureConversion {
  db::StructureRecord structure;
  ResolvedGrid grid;
  Voxelization voxelization;
  FeatureEngine::Admission held;  // the runs, and a mask made from them, stay within it
};

Result<StructureConversion> convert_structure(db::Store& store, FeatureEngine& features, WorkerPool& pool,
                                              int64_t structure_id, const GridChoice& choice, FillRule fill_rule,
                                              bool mask_export, const std::function<Status()>& stop);

// The same for coverage fractions with n x n lines per voxel (FeatureEngine::cover); the admission
// counts dense fractions of `fraction_bytes` (1 or 4) per voxel for the NIfTI that follows.
struct StructureCoverage {
  db::StructureRecord structure;
  ResolvedGrid grid;
  CoverageVolume coverage;
  FeatureEngine::Admission held;
};

Result<StructureCoverage> cover_structure(db::Store& store, FeatureEngine& features, WorkerPool& pool,
                                          int64_t structure_id, const GridChoice& choice, FillRule fill_rule,
                                          int lines_per_voxel, int fraction_bytes, const std::function<Status()>& stop);

// The fractions as a gzipped NIfTI: uint8 0-255 (to_fraction_bytes) or, with `float32`, 0-1.
Result<std::string> fraction_nifti_bytes(const CoverageVolume& coverage, bool float32, int64_t max_voxels);

// The volume as a gzipped NIfTI mask (1 inside, 0 outside) on its grid. RESOURCE_EXHAUSTED when
// the grid has more than max_voxels voxels.
Result<std::string> mask_nifti_bytes(const RunLengthVolume& volume, int64_t max_voxels);

}  // namespace soiq::server
