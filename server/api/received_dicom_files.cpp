#include "server/api/received_dicom_files.h"

#include <filesystem>
#include <fstream>
#include <set>

namespace soiq::server {
namespace {

namespace fs = std::filesystem;

// The file being received: where it goes, how many bytes were announced and have come.
struct OpenFile {
  std::string path;
  int64_t expected = 0;
  int64_t received = 0;
  std::ofstream out;
};

Status finish(OpenFile& f) {
  f.out.close();
  if (!f.out) return internal_error("cannot write the received file '" + f.path + "' (disk full?)");
  if (f.received != f.expected) {
    return invalid_argument("file '" + f.path + "' announced " + std::to_string(f.expected) + " bytes but " +
                            std::to_string(f.received) + " were sent");
  }
  return ok_status();
}

}  // namespace

Status check_relative_path(const std::string& path) {
  if (path.empty()) return invalid_argument("an imported file has an empty path");
  if (path.front() == '/') return invalid_argument("imported file path '" + path + "' must be relative");
  if (path.find('\0') != std::string::npos) return invalid_argument("imported file path contains a NUL byte");
  size_t start = 0;
  while (start <= path.size()) {
    const size_t end = std::min(path.find('/', start), path.size());
    const std::string part = path.substr(start, end - start);
    if (part.empty() || part == "." || part == "..")
      return invalid_argument("imported file path '" + path + "' has an empty, '.' or '..' part");
    start = end + 1;
  }
  return ok_status();
}

Result<ReceivedFiles> receive_dicom_files(grpc::ServerReaderInterface<v1::ImportDicomRequest>& reader,
                                          const std::string& dir, int64_t max_bytes) {
  ReceivedFiles out;
  std::set<std::string> seen;
  OpenFile current;
  bool open = false;
  v1::ImportDicomRequest part;
  while (reader.Read(&part)) {
    if (part.part_case() == v1::ImportDicomRequest::kOptions) {
      if (open || out.options_given) return invalid_argument("DICOM import options must come once, before any file");
      out.options_given = true;
      out.replace = part.options().replace();
      continue;
    }
    if (part.part_case() == v1::ImportDicomRequest::kFile) {
      if (open) SOIQ_RETURN_IF_ERROR(finish(current));
      const v1::ImportFileHeader& h = part.file();
      SOIQ_RETURN_IF_ERROR(check_relative_path(h.path()));
      if (!seen.insert(h.path()).second) return invalid_argument("file '" + h.path() + "' is sent twice");
      if (h.size_bytes() < 0) return invalid_argument("file '" + h.path() + "' has a negative size");
      const fs::path target = fs::path(dir) / h.path();
      std::error_code ec;
      fs::create_directories(target.parent_path(), ec);
      if (ec) return internal_error("cannot create the folder for '" + h.path() + "': " + ec.message());
      current.path = h.path();
      current.expected = h.size_bytes();
      current.received = 0;
      current.out = std::ofstream(target, std::ios::binary | std::ios::trunc);
      if (!current.out) return internal_error("cannot create the received file '" + h.path() + "'");
      open = true;
      out.paths.push_back(h.path());
      continue;
    }
    if (!open) return invalid_argument("DICOM import must send a file header before its bytes");
    const std::string& chunk = part.chunk();
    out.bytes += int64_t(chunk.size());
    if (out.bytes > max_bytes) {
      return resource_exhausted("DICOM import is larger than the server's limit of " + std::to_string(max_bytes) +
                                " bytes (soiqd --max-upload-bytes); import fewer files at a time");
    }
    current.received += int64_t(chunk.size());
    if (current.received > current.expected) SOIQ_RETURN_IF_ERROR(finish(current));
    current.out.write(chunk.data(), std::streamsize(chunk.size()));
  }
  if (!open) return invalid_argument("DICOM import sent no files");
  SOIQ_RETURN_IF_ERROR(finish(current));
  return out;
}

}  // namespace soiq::server
