#pragma once
// The files `soiq import PATH...` sends, with the relative names the server gets
// (ImportFileHeader.path): a file argument is sent under its own name; a folder is walked
// recursively (symlinks followed, sorted) and each regular file is sent as
// "<folder name>/<path inside it>", so DICOMDIRs still find the files they reference. When two
// arguments share a name, the later ones get "_2", "_3", ... appended to it.
//
// Errors   NOT_FOUND naming a path that does not exist; INVALID_ARGUMENT for a path that is neither
//          a file nor a folder, or a folder with no regular file. INTERNAL when a folder cannot be read.
// Cost     O(files) directory reads; nothing is opened.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::client {

struct FileToSend {
  std::string local_path;
  std::string sent_path;
  int64_t size_bytes = 0;
};

Result<std::vector<FileToSend>> dicom_files_to_send(const std::vector<std::string>& paths);

}  // namespace soiq::client
