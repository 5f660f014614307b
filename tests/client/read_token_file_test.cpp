#include "client/read_token_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace soiq::client {
namespace {

std::string write_temp(const std::string& name, const std::string& content) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

TEST(ReadTokenFile, TrailingNewlineIsTrimmed) {
  const std::string path = write_temp("soiq_token_newline", "s3cret-token\n");
  const auto t = read_token_file(path);
  ASSERT_TRUE(t.ok()) << t.status().to_string();
  EXPECT_EQ(*t, "s3cret-token");
  std::remove(path.c_str());
}

TEST(ReadTokenFile, MissingFileIsNotFoundAndNamed) {
  const auto t = read_token_file("/nonexistent/soiq/token");
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.status().code(), StatusCode::kNotFound);
  EXPECT_NE(t.status().message().find("/nonexistent/soiq/token"), std::string::npos);
}

TEST(ReadTokenFile, EmptyFileIsInvalid) {
  const std::string path = write_temp("soiq_token_empty", "\n");
  const auto t = read_token_file(path);
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(t.status().message().find("empty"), std::string::npos);
  std::remove(path.c_str());
}

TEST(ReadTokenFile, TwoLinesAreRefused) {
  const std::string path = write_temp("soiq_token_lines", "one\ntwo\n");
  const auto t = read_token_file(path);
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.status().message().find("line break"), std::string::npos);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace soiq::client
