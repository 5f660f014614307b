#pragma once
// The case table of soiq's marching cubes (core/io/marching_cubes.h: VTK's vtkFlyingEdges3D at
// iso 0.5) committed as data (core/features/marching_cubes_table.cpp, written by
// tools/make_marching_cubes_table.cpp), so that the mask-surface features (mask_surface_shape.h)
// reproduce that surface's volume and area without VTK at run time. A test compares it with the
// table read off the installed VTK (tests/core/io/marching_cubes_cases_test.cpp).
// Output   the table (cube_case_table.h). Cases 0 and 255 have no triangles.
// Cost     built once per process from ~2,500 constants; then free. Thread-safe (static init).

#include "core/features/cube_case_table.h"

namespace soiq {

const CubeCaseTable& marching_cubes_table();

}  // namespace soiq
