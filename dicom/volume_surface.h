#pragma once
// The surface model of a volume model that came without one (an RT Structure Set ROI filled on its
// grid, a DICOM SEG segment): marching cubes at iso 0.5 of its mask (core/io/marching_cubes.h), in
// LPS mm, closed and outward. Computed on the mask cropped to the volume's bounding box, which
// gives the same surface (marching cubes pads by one voxel of zeros) at a fraction of the cost.
//
// Inputs   v: a volume on any grid (oblique included).
// Output   The surface; empty (no triangles) when v has no voxel.
// Errors   marching_cubes' (INTERNAL when VTK fails).
// Cost     O(lines of v's grid + voxels of its bounding box). Thread-safe.

#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq::dicom {

Result<TriangleMesh> volume_surface(const RunLengthVolume& v);

}  // namespace soiq::dicom
