#include "client/cli/cli_args.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "proto/text/query_options.h"

namespace soiq::cli {

Result<double> parse_number(const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v)) {
    return invalid_argument(what + " must be a number, got '" + text + "'");
  }
  return v;
}

Result<int> parse_int(const std::string& text, const std::string& what, int lo, int hi) {
  SOIQ_ASSIGN_OR_RETURN(double v, parse_number(text, what));
  if (v < lo || v > hi || v != std::floor(v)) {
    return invalid_argument(what + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
  }
  return int(v);
}

Result<Vec3> parse_spacing(const std::string& text) {
  // The query table's reading of a spacing, so --spacing means the same to every command.
  soiq::v1::GridSpec grid;
  const Status s = proto_text::set_grid_spacing(text, grid);
  if (!s.ok()) return Status(s.code(), "--spacing: " + s.message());
  if (grid.has_spacing_xyz()) return Vec3{grid.spacing_xyz().x(), grid.spacing_xyz().y(), grid.spacing_xyz().z()};
  return Vec3{grid.spacing_mm(), grid.spacing_mm(), grid.spacing_mm()};
}

bool ends_with(const std::string& path, const std::string& suffix) {
  return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool is_mesh_path(const std::string& path) {
  for (const char* ext : {".stl", ".obj", ".ply", ".vtk", ".vtp", ".STL", ".OBJ", ".PLY", ".VTK", ".VTP"}) {
    if (ends_with(path, ext)) return true;
  }
  return false;
}

Status make_output_folder(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) return ok_status();
  std::error_code ec;
  if (std::filesystem::is_directory(folder, ec)) return ok_status();
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder)) {
    return invalid_argument("cannot make the output folder '" + folder.string() + "' for '" + path +
                            "': " + (ec ? ec.message() : std::string("a file is in the way")));
  }
  return ok_status();
}

}  // namespace soiq::cli
