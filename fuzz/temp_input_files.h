#pragma once
// For the DICOM readers that take paths: each run's input written to files in one private folder
// (mkdtemp, mode 0700, removed at exit), overwritten by the next run. Single-threaded, as libFuzzer
// runs a harness.

#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace soiq::fuzz {

class TempInputFiles {
 public:
  TempInputFiles() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/soiq-fuzz-XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("soiq fuzz: mkdtemp");
      std::abort();
    }
    dir_ = pattern;
  }
  ~TempInputFiles() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  TempInputFiles(const TempInputFiles&) = delete;
  TempInputFiles& operator=(const TempInputFiles&) = delete;

  const std::string& dir() const { return dir_; }

  // Replaces the folder's files with `parts`, one file each (slice_0.dcm, slice_1.dcm, ...), and
  // returns their paths in order.
  std::vector<std::string> write(const std::vector<std::string_view>& parts) {
    std::error_code ignored;
    for (const auto& entry : std::filesystem::directory_iterator(dir_, ignored))
      std::filesystem::remove_all(entry.path(), ignored);
    std::vector<std::string> paths;
    for (size_t n = 0; n < parts.size(); ++n) {
      paths.push_back(dir_ + "/slice_" + std::to_string(n) + ".dcm");
      std::ofstream out(paths.back(), std::ios::binary | std::ios::trunc);
      out.write(parts[n].data(), std::streamsize(parts[n].size()));
      if (!out) {
        std::fprintf(stderr, "soiq fuzz: cannot write %s\n", paths.back().c_str());
        std::abort();
      }
    }
    return paths;
  }

 private:
  std::string dir_;
};

}  // namespace soiq::fuzz
