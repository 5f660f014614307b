#pragma once
// STS_002's CT as the server receives it: its 48 slices and its RT Structure Set (tests/data/sts,
// CC BY 3.0) copied into a folder under flat names, as an upload or a PACS pull leaves them.

#include <filesystem>
#include <string>
#include <vector>

namespace soiq::testing {

// Copies the files into `dir` and returns their names, relative to `dir`.
inline std::vector<std::string> copy_sts_002_ct(const std::string& data_dir, const std::string& dir) {
  namespace fs = std::filesystem;
  const fs::path ct = fs::path(data_dir) / "sts/STS_002/dicom/CT";
  std::vector<std::string> sent;
  for (const char* part : {"image", "mask"}) {
    for (const auto& f : fs::directory_iterator(ct / part)) {
      const std::string name = std::string(part) + "_" + f.path().filename().string();
      fs::copy_file(f.path(), fs::path(dir) / name);
      sent.push_back(name);
    }
  }
  return sent;
}

}  // namespace soiq::testing
