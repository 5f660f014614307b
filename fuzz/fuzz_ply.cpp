// Feeds each input to parse_mesh as a .ply upload (core/io/parse_mesh.h), as soiqd does with a
// surface a client sends: PLY, ASCII or binary of either byte order, soiq's own parser, no third-party code. A bug is
// any crash or sanitizer report (out-of-bounds read, overflow, leak), a run over libFuzzer's -timeout or its
// -rss_limit_mb (every allocation must be bounded by the input's size), or an OK result that breaks
// parse_mesh's contract (fuzz/mesh_contract.h). Any error status is a correct answer.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/io/parse_mesh.h"
#include "fuzz/mesh_contract.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto mesh = soiq::parse_mesh(bytes, "ply", /*ras=*/false, "fuzz.ply");
  if (mesh.ok()) soiq::fuzz::check_mesh_contract(*mesh);
  return 0;
}
