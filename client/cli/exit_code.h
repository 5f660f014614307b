#pragma once
// The one mapping from a soiq::Status to the `soiq` command's exit code (STYLE.md section 3; the
// README repeats the table):
//   0 OK; 2 INVALID_ARGUMENT (and usage errors); 3 NOT_FOUND; 4 ALREADY_EXISTS or
//   FAILED_PRECONDITION; 5 RESOURCE_EXHAUSTED; 6 UNAVAILABLE, DEADLINE_EXCEEDED or CANCELLED;
//   7 UNAUTHENTICATED or PERMISSION_DENIED; 1 any other code; 8 a partial query answer (kExitPartial);
//   130 a long command stopped by Ctrl-C (kExitInterrupted, interrupt.h).

#include "core/base/status.h"

namespace soiq::cli {

inline constexpr int kExitUsage = 2;  // a malformed command line, as for INVALID_ARGUMENT
// `soiq query` answered, but stage 2 skipped some candidates (the summary says how many and why):
// the rows are those of the candidates it could answer for.
inline constexpr int kExitPartial = 8;

int exit_code(const soiq::Status& status);

}  // namespace soiq::cli
