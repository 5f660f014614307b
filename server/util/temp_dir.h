#pragma once
// A uniquely named directory in $TMPDIR (or /tmp), removed with everything in it when the object
// goes. DICOM imports receive their files into one, since DCMTK and the DICOMDIR references work
// on paths (server/api/received_dicom_files.h).

#include <string>

#include "core/base/status.h"

namespace soiq::server {

class TempDir {
 public:
  // INTERNAL (naming the pattern) when the directory cannot be made.
  static Result<TempDir> create();
  TempDir(TempDir&& other) noexcept : path_(std::move(other.path_)) { other.path_.clear(); }
  TempDir& operator=(TempDir&&) = delete;
  TempDir(const TempDir&) = delete;
  ~TempDir();

  const std::string& path() const { return path_; }

 private:
  explicit TempDir(std::string path) : path_(std::move(path)) {}
  std::string path_;
};

}  // namespace soiq::server
