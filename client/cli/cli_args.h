#pragma once
// Parsing helpers shared by the `soiq` commands: one message style for every bad argument.

#include <cstdio>
#include <string>

#include "client/cli/exit_code.h"
#include "core/base/status.h"
#include "core/base/vec3.h"

namespace soiq::cli {

// A finite number; INVALID_ARGUMENT "<what> must be a number, got '<text>'".
Result<double> parse_number(const std::string& text, const std::string& what);

// A whole number in [lo, hi].
Result<int> parse_int(const std::string& text, const std::string& what, int lo, int hi);

// "S" or "SX,SY,SZ" in mm, each > 0.
Result<Vec3> parse_spacing(const std::string& text);

// True when `path` ends with one of the mesh extensions soiq reads (.stl .obj .ply .vtk .vtp).
bool is_mesh_path(const std::string& path);

// Creates the folder an -o output goes into when it does not exist yet (as `mkdir -p`), so every
// command treats a new output folder alike; INVALID_ARGUMENT naming the folder when it cannot be
// made (a file is in the way, no permission). Called before any work, so a refusal costs nothing.
Status make_output_folder(const std::string& path);

// True when `path` ends with `suffix`.
bool ends_with(const std::string& path, const std::string& suffix);

// Runs command `name`: parsed arguments (or the parse error), then `act`. Any error is one line on
// stderr, "soiq NAME: message" (with a pointer to `soiq NAME --help` after a parse error), and the exit code
// comes from exit_code(): the one place a command's outcome becomes a process status.
template <typename Args, typename Act>
int run_command(const char* name, const Result<Args>& args, Act&& act) {
  if (!args.ok()) {
    std::fprintf(stderr, "soiq %s: %s (usage: soiq %s --help)\n", name, args.status().message().c_str(), name);
    return exit_code(args.status());
  }
  const Status s = act(*args);
  if (!s.ok()) {
    std::fprintf(stderr, "soiq %s: %s\n", name, s.message().c_str());
    return exit_code(s);
  }
  return 0;
}

}  // namespace soiq::cli
