#pragma once
// OpenVDB as a benchmark peer: openvdb::tools::meshToVolume, a narrow-band signed distance field
// in the grid's index space (voxel size 1, so voxel (i,j,k)'s centre is the lattice point (i,j,k)
// of OpenVDB's grid, on oblique and sheared grids too), then a voxel is inside iff its signed
// distance is <= 0. OpenVDB fills cavities, so each connected surface of the mesh is converted on
// its own and the results combined by parity (peer_openvdb.cpp says why, and how the result
// differs from V1). Untimed: the vertices mapped into index space (physical_to_index) and the
// triangles split by connected surface, as OpenVDB's point and triangle lists. Timed: meshToVolume
// of each surface (its sign flood fill included) and writing the dense mask. meshToVolume runs on
// TBB, limited to `threads` (tbb::global_control) during the timed call. On an unevenly spaced
// grid the index map is affine only between slices, so a triangle spanning slices would be bent
// (no benchmark case has one). Only in builds with OpenVDB (SOIQ_HAVE_OPENVDB); otherwise
// prepare_openvdb returns UNIMPLEMENTED.

#include "bench/conversion.h"

namespace soiq::bench {

bool openvdb_available();
Result<Conversion> prepare_openvdb(const TriangleMesh& mesh, const ImageGeometry& geometry, int threads);

}  // namespace soiq::bench
