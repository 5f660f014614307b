#pragma once
// Test support for tests/dicom: where the data is, and a temporary directory removed at the end of
// the test.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <random>
#include <string>

namespace soiq::dicom::testing {

inline std::string data_dir(const std::string& sub) { return std::string(SOIQ_TEST_DATA_DIR) + "/" + sub; }

class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("soiq_dicom_" + std::string(info ? info->name() : "x") + "_" + std::to_string(::getpid()) + "_" +
             std::to_string(counter++) + "_" + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace soiq::dicom::testing
