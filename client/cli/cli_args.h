#pragma once
// Parsing helpers shared by the `soiq` commands: one message style for every bad argument.

#include <cstdio>
#include <string>

#include "client/cli/exit_code.h"
#include "client/cli/interrupt.h"
#include "client/soiq_client.h"
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
    return interrupted() ? kExitInterrupted : exit_code(s);
  }
  return 0;
}

// run_command for a command that can run long: while `act(args, options)` runs, Ctrl-C
// (interrupt.h) cancels the call in progress through `options.cancel` (`remote` with the flag
// set). When interrupted, `act` returns the status of interrupted_by_user() naming what it kept;
// the exit code is then kExitInterrupted.
template <typename Args, typename Act>
int run_long_command(const char* name, const Result<Args>& args, const client::ClientOptions& remote, Act&& act) {
  return run_command(name, args, [&](const Args& a) {
    const InterruptScope scope;
    client::ClientOptions options = remote;
    options.cancel = scope.flag();
    return act(a, options);
  });
}

// CANCELLED "interrupted; <kept>": what an interrupted command says it kept ("nothing was
// imported").
inline Status interrupted_by_user(const std::string& kept) {
  return Status(StatusCode::kCancelled, "interrupted; " + kept);
}

}  // namespace soiq::cli
