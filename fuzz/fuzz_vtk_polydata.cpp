// Feeds each input to parse_mesh (core/io/parse_mesh.h) as soiqd does with a surface upload in
// VTK's formats: as .vtp (VTK's XML parser for the elements, soiq's own decoding of the arrays,
// core/io/vtk_xml_polydata.h) when its first non-blank byte is '<', otherwise as legacy .vtk (soiq's
// legacy_vtk_geometry check, then VTK's reader), so one corpus covers both. VTK itself is not
// instrumented (Debian's build): it is reached, but only its crashes, not its silent overreads, show.
// A bug is any crash or sanitizer report, a run over -timeout or -rss_limit_mb, or an OK result that
// breaks parse_mesh's contract (fuzz/mesh_contract.h); a crash inside VTK counts too, since soiqd
// would die of it.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/io/parse_mesh.h"
#include "fuzz/mesh_contract.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const size_t first = bytes.find_first_not_of(" \t\r\n");
  const bool xml = first != std::string_view::npos && bytes[first] == '<';
  auto mesh = soiq::parse_mesh(bytes, xml ? "vtp" : "vtk", /*ras=*/false, xml ? "fuzz.vtp" : "fuzz.vtk");
  if (mesh.ok()) soiq::fuzz::check_mesh_contract(*mesh);
  return 0;
}
