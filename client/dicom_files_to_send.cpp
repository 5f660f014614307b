#include "client/dicom_files_to_send.h"

#include <algorithm>
#include <filesystem>
#include <set>

namespace soiq::client {
namespace {

namespace fs = std::filesystem;

// The argument's own name: "a/b/" and "a/b" both give "b"; "/" or "." give "files".
std::string base_name(const std::string& path) {
  fs::path p = fs::path(path).lexically_normal();
  if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();
  std::string name = p.filename().string();
  if (name.empty() || name == "." || name == "..") name = fs::absolute(p).lexically_normal().filename().string();
  return name.empty() || name == "." || name == ".." ? "files" : name;
}

std::string unique_name(const std::string& name, std::set<std::string>& used) {
  std::string out = name;
  for (int n = 2; !used.insert(out).second; ++n) out = name + "_" + std::to_string(n);
  return out;
}

}  // namespace

Result<std::vector<FileToSend>> dicom_files_to_send(const std::vector<std::string>& paths) {
  std::vector<FileToSend> out;
  std::set<std::string> used;
  for (const std::string& path : paths) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) return not_found("'" + path + "' does not exist");
    const std::string name = unique_name(base_name(path), used);
    if (fs::is_regular_file(st)) {
      out.push_back({path, name, int64_t(fs::file_size(path))});
      continue;
    }
    if (!fs::is_directory(st)) return invalid_argument("'" + path + "' is neither a file nor a folder");
    std::vector<FileToSend> found;
    fs::recursive_directory_iterator it(path, fs::directory_options::follow_directory_symlink, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
      if (!it->is_regular_file()) continue;
      const std::string inside = fs::relative(it->path(), path).generic_string();
      found.push_back({it->path().string(), name + "/" + inside, int64_t(it->file_size())});
    }
    if (ec) return internal_error("cannot read the folder '" + path + "': " + ec.message());
    if (found.empty()) return invalid_argument("the folder '" + path + "' has no files");
    std::sort(found.begin(), found.end(),
              [](const FileToSend& a, const FileToSend& b) { return a.sent_path < b.sent_path; });
    out.insert(out.end(), found.begin(), found.end());
  }
  return out;
}

}  // namespace soiq::client
