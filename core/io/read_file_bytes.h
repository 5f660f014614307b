#pragma once
// The whole content of a file, for the small-header formats soiq parses itself (NRRD, MetaImage,
// OBJ pre-scan) and for size checks before a third-party reader sees the file.
//
// Inputs   path; `what` names the kind of file in messages ("image", "mesh", "NRRD data file").
// Output   the bytes, possibly empty (callers decide whether empty is an error).
// Errors   NOT_FOUND the file does not exist; INVALID_ARGUMENT it is a directory or cannot be read;
//          RESOURCE_EXHAUSTED it is larger than `max_bytes`.
// Cost     O(file size) memory and time; thread-safe.

#include <cstdint>
#include <string>

#include "core/base/status.h"

namespace soiq {

inline constexpr int64_t kMaxInputFileBytes = int64_t(4) << 30;  // 4 GiB

Result<std::string> read_file_bytes(const std::string& path, const std::string& what,
                                    int64_t max_bytes = kMaxInputFileBytes);

// Only the checks of read_file_bytes, without reading: OK when `path` is an existing regular file,
// and its size in bytes through the Result.
Result<int64_t> input_file_size(const std::string& path, const std::string& what);

}  // namespace soiq
