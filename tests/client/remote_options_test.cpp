#include "client/cli/remote_options.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace soiq::cli {
namespace {

// argv storage that take_remote_options may shrink.
struct Argv {
  explicit Argv(std::vector<std::string> a) : args(std::move(a)) {
    for (std::string& s : args) ptrs.push_back(s.data());
    ptrs.push_back(nullptr);
    argc = int(args.size());
  }
  std::vector<std::string> rest() const { return {ptrs.begin(), ptrs.begin() + argc}; }
  std::vector<std::string> args;
  std::vector<char*> ptrs;
  int argc;
};

TEST(TakeRemoteOptions, FoundBeforeAndAfterTheCommandAndRemoved) {
  Argv a({"soiq", "--server", "db1:7000", "ls", "structures", "--timeout=2.5", "--token-file", "/t", "--tls-ca=/ca"});
  const auto o = take_remote_options(a.argc, a.ptrs.data());
  ASSERT_TRUE(o.ok()) << o.status().to_string();
  EXPECT_EQ(o->address, "db1:7000");
  EXPECT_EQ(o->token_file, "/t");
  EXPECT_EQ(o->tls_ca_file, "/ca");
  EXPECT_EQ(o->deadline.count(), 2500);
  EXPECT_EQ(o->stream_deadline.count(), 2500);
  EXPECT_EQ(a.rest(), (std::vector<std::string>{"soiq", "ls", "structures"}));
}

TEST(TakeRemoteOptions, MissingValueIsAUsageError) {
  Argv a({"soiq", "info", "--server"});
  const auto o = take_remote_options(a.argc, a.ptrs.data());
  ASSERT_FALSE(o.ok());
  EXPECT_NE(o.status().message().find("--server needs a value"), std::string::npos);
}

TEST(TakeRemoteOptions, TimeoutMustBePositive) {
  Argv a({"soiq", "info", "--timeout", "0"});
  const auto o = take_remote_options(a.argc, a.ptrs.data());
  ASSERT_FALSE(o.ok());
  EXPECT_NE(o.status().message().find("--timeout"), std::string::npos);
}

TEST(FirstOperand, SkipsTheValuesOfOptions) {
  Argv a({"features", "--spacing", "1", "--format", "json", "42"});
  EXPECT_EQ(first_operand(a.argc, a.ptrs.data(), {"--spacing", "--format"}), "42");
  Argv b({"convert", "-o", "out.nii.gz", "mesh.stl"});
  EXPECT_EQ(first_operand(b.argc, b.ptrs.data(), {"-o"}), "mesh.stl");
}

TEST(IsStructureId, DigitsOnly) {
  EXPECT_TRUE(is_structure_id("42"));
  EXPECT_FALSE(is_structure_id("42.stl"));
  EXPECT_FALSE(is_structure_id(""));
  EXPECT_FALSE(is_structure_id("-1"));
  EXPECT_FALSE(parse_structure_id("0").ok());
}

}  // namespace
}  // namespace soiq::cli
