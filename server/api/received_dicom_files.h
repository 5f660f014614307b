#pragma once
// The client stream of ImportDicom written to disk: each ImportFileHeader opens a file under `dir`
// at its relative path, the chunks after it fill it, one file after another.
//
// Errors   INVALID_ARGUMENT: a chunk before any header, a path that is empty, absolute, has "." or
//          ".." parts or repeats an earlier one (the message names it), chunks that do not add up
//          to the header's size_bytes, or a stream with no file at all. RESOURCE_EXHAUSTED as soon
//          as the bytes pass `max_bytes` (soiqd --max-upload-bytes). INTERNAL when the disk refuses
//          a write. Whatever was written stays in `dir` (the caller's TempDir removes it).
// Cost     O(bytes); one chunk in memory at a time.

#include <grpcpp/support/sync_stream.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

struct ReceivedFiles {
  std::vector<std::string> paths;  // relative, in the order received
  int64_t bytes = 0;
  bool options_given = false;
  bool replace = false;  // ImportOptions.replace
};

Result<ReceivedFiles> receive_dicom_files(grpc::ServerReaderInterface<v1::ImportDicomRequest>& reader,
                                          const std::string& dir, int64_t max_bytes);

// OK when `path` is a safe relative path as ImportFileHeader asks; INVALID_ARGUMENT otherwise.
Status check_relative_path(const std::string& path);

}  // namespace soiq::server
