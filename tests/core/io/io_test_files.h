#pragma once
// Helpers shared by the core/io tests: a per-process scratch directory and small file writers.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <iterator>
#include <string>
#include <string_view>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq::testing_io {

// A fresh directory under ::testing::TempDir(), made once per test process.
inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    std::string pattern = ::testing::TempDir() + "soiq_io_XXXXXX";
    const char* made = mkdtemp(pattern.data());
    return std::string(made ? made : ::testing::TempDir().c_str()) + "/";
  }();
  return dir;
}

inline std::string scratch_path(const std::string& name) { return scratch_dir() + name; }

inline std::string write_bytes(const std::string& name, std::string_view bytes) {
  const std::string path = scratch_path(name);
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  return path;
}

// The whole content of a file ("" when it cannot be read).
inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A reader's refusal: INVALID_ARGUMENT, one line, with `phrase` in it.
inline void expect_invalid(const Result<TriangleMesh>& mesh, const std::string& phrase) {
  ASSERT_FALSE(mesh.ok()) << phrase;
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find(phrase), std::string::npos) << mesh.status().message();
  EXPECT_EQ(mesh.status().message().find('\n'), std::string::npos) << "one line: " << mesh.status().message();
}

inline std::string data_path(const std::string& relative) { return std::string(SOIQ_TEST_DATA_DIR) + "/" + relative; }

}  // namespace soiq::testing_io
