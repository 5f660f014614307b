#pragma once
// A request's GridSpec as the application's GridChoice (server/app/grid_choice.h): a stored series
// by uid or modality, or an axis-aligned grid at a spacing (one for all axes, or per axis) with a
// margin. Unset: the axis-aligned 1 mm grid with a 2-voxel margin.
// Errors: INVALID_ARGUMENT for a margin outside [0, 1000] voxels, a spacing outside
// [0.01, 100] mm, or an empty series uid.

#include "core/base/status.h"
#include "server/app/grid_choice.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

Result<GridChoice> grid_choice(const v1::GridSpec& spec);

}  // namespace soiq::server
