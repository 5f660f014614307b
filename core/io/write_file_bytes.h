#pragma once
// Writes a whole file atomically: the bytes go to a temporary file beside `path`, which is renamed
// over `path` only once completely written, so a crash never leaves a half-written file behind.
//
// Errors  NOT_FOUND the directory does not exist; RESOURCE_EXHAUSTED the disk is full;
//         INTERNAL any other I/O failure (with the system's reason). `what` names the file kind.
// Cost    O(bytes); thread-safe for distinct paths.

#include <string>
#include <string_view>

#include "core/base/status.h"

namespace soiq {

Status write_file_bytes(const std::string& path, std::string_view bytes, const std::string& what);

// The error for a failed write of `path` from errno `err`: NOT_FOUND for a missing directory,
// RESOURCE_EXHAUSTED for a full disk or quota, INTERNAL otherwise.
Status write_error(const std::string& path, int err, const std::string& what);

}  // namespace soiq
