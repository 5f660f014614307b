#pragma once
// A uniquely named file in $TMPDIR (or /tmp), removed when the object goes. The mesh and image
// readers and writers are VTK's and libnifti's, which work on paths, so uploaded bytes pass
// through one of these; the suffix carries the format (".stl", ".nii.gz").

#include <string>

#include "core/base/status.h"

namespace soiq::server {

class TempFile {
 public:
  static Result<TempFile> create(const std::string& suffix);
  TempFile(TempFile&& other) noexcept : path_(std::move(other.path_)) { other.path_.clear(); }
  TempFile& operator=(TempFile&&) = delete;
  TempFile(const TempFile&) = delete;
  ~TempFile();

  const std::string& path() const { return path_; }
  Status write(const std::string& bytes) const;
  Result<std::string> read() const;

 private:
  explicit TempFile(std::string path) : path_(std::move(path)) {}
  std::string path_;
};

}  // namespace soiq::server
