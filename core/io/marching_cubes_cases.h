#pragma once
// The case table of soiq's marching cubes (marching_cubes.h: VTK's vtkFlyingEdges3D at iso 0.5),
// read off VTK once per process: one run over an image holding all 256 single-cube patterns. With it,
// mask_surface_shape(runs) reproduces the marching-cubes surface's volume and area exactly (up
// to rounding) without building the surface.
// Output   the table (cube_case_table.h). Cases 0 and 255 have no triangles.
// Errors   none; a VTK failure is a broken installation and aborts (assert) in debug builds and
//          yields an empty case in release builds, which the tests would catch.
// Cost     one small VTK run on the first call (a pipeline per pattern took ~10 ms, paid by every
//          `soiq features` call); then free. Thread-safe (static init).

#include "core/features/cube_case_table.h"

namespace soiq {

const CubeCaseTable& marching_cubes_cases();

// The table as VTK gives it for each pattern alone: 256 runs (~5 ms), the tests' oracle for the
// one-run table above.
CubeCaseTable marching_cubes_cases_one_by_one();

}  // namespace soiq
