#pragma once
// ITK as a benchmark peer: itk::TriangleMeshToBinaryImageFilter on the grid (origin, spacing,
// direction, size), inside 1 / outside 0, default tolerance. The itk::Mesh is built untimed; the
// filter run and the copy of its buffer into the mask are timed. Only in builds with ITK
// (SOIQ_HAVE_ITK); otherwise prepare_itk returns UNIMPLEMENTED.

#include "bench/conversion.h"

namespace soiq::bench {

bool itk_available();
Result<Conversion> prepare_itk(const TriangleMesh& mesh, const ImageGeometry& geometry);

}  // namespace soiq::bench
