#pragma once
// Test support for tests/dicom: where the data is, and a temporary directory removed at the end of
// the test.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <random>
#include <string>

#include "tests/support/temp_dir.h"

namespace soiq::dicom::testing {

inline std::string data_dir(const std::string& sub) { return std::string(SOIQ_TEST_DATA_DIR) + "/" + sub; }

using soiq::testing::TempDir;

}  // namespace soiq::dicom::testing
