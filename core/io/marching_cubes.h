#pragma once
// The surface of a mask: marching cubes at iso 0.5 on the mask padded by one voxel of zeros (so the
// surface is closed where the mask touches the grid border), as IBSI and PyRadiomics build it.
// Vertices sit at edge midpoints between an inside and an outside voxel centre, in physical LPS mm
// (the grid's direction matrix applied); triangles face outward (positive signed volume).
// Built on VTK's marching cubes; the result is watertight (every edge shared by two triangles).
// Errors: INVALID_ARGUMENT on an invalid geometry or a voxel buffer of the wrong size.
// An empty mask gives an empty mesh.

#include "core/base/image.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> marching_cubes(const Mask& mask);

}  // namespace soiq
