#pragma once
// The tests' fixtures: a path under tests/data/ (SOIQ_TEST_DATA_DIR, defined by the test target)
// and a file's bytes, read whole.

#include <fstream>
#include <sstream>
#include <string>

namespace soiq::testing {

// `relative` under tests/data/, e.g. test_data("dicom/CT_small.dcm").
inline std::string test_data(const std::string& relative) { return std::string(SOIQ_TEST_DATA_DIR) + "/" + relative; }

// The bytes of the file at `path`; empty when it cannot be read (the test's own check then fails).
inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace soiq::testing
