#pragma once
// A fresh private directory under $TMPDIR (mkdtemp, mode 0700), removed with everything in it when
// the object goes. Every test that writes files (stores, uploads, DICOM, PACS storage) uses one.

#include <stdlib.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace soiq::testing {

class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "soiq-test-XXXXXX").string();
    if (::mkdtemp(pattern.data()) != nullptr) path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    if (!path_.empty()) std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace soiq::testing
