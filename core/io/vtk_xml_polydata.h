#pragma once
// Reads the geometry of a VTK XML PolyData file (.vtp) held in memory: the points and the polygon
// and triangle-strip cells of every piece, joined into one set. VTK's XML parser (expat) reads the
// elements and their attributes; the arrays are decoded by soiq (vtk_xml_data_array.h), because
// VTK 9.1's reader allocates whatever the file's headers and offsets claim before it looks at the
// bytes behind them. Vertices, lines, point and cell data are skipped without being decoded.
//
// Inputs   the file's bytes; `name` (file or upload name) for messages.
// Output   points as x,y,z triples; for polygons and strips, offsets (cells + 1 values, the first
//          0, never decreasing) and connectivity (point indices, each < the number of points).
// Errors   INVALID_ARGUMENT naming `name`: not XML, not a PolyData file, an attribute or array
//          that is missing, malformed or inconsistent with the counts of its piece, offsets that
//          decrease or do not end at the connectivity's length, a point index out of range.
//          RESOURCE_EXHAUSTED: more than 2^31 points, or compressed arrays declaring more bytes
//          than 64 times the file's size plus 1 MiB (no real surface compresses that well; a
//          decompression bomb does).
// Cost     O(bytes + decoded size); the decoded arrays are bounded by the limit above. Thread-safe.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/status.h"

namespace soiq {

struct VtkXmlCells {
  std::vector<int64_t> offsets{0};
  std::vector<int64_t> connectivity;
};

struct VtkXmlPolyData {
  std::vector<double> points;  // x0 y0 z0 x1 y1 z1 ...
  VtkXmlCells polys;
  VtkXmlCells strips;
};

Result<VtkXmlPolyData> read_vtk_xml_polydata(std::string_view bytes, const std::string& name);

}  // namespace soiq
