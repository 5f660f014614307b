#pragma once
// `soiq mesh MASK -o OUT.{stl,vtk,vtp,ply,obj} [--label N]`: a mask (or label map) -> its
// marching-cubes surface (iso 0.5, LPS mm, outward normals), offline.
// Voxels equal to N are inside (default: every nonzero voxel). Prints one line to stdout,
// "N triangles, V vertices, mesh volume X mm3 -> OUT"; on failure one line "soiq mesh: <message>"
// to stderr and the exit code of exit_code.h.

namespace soiq::cli {

// argv[0] is "mesh".
int run_mesh_command(int argc, char** argv);

}  // namespace soiq::cli
