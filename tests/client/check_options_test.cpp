#include "client/cli/check_options.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace soiq::cli {
namespace {

// argv of `soiq NAME args...`: the command's own arguments start at index 2.
struct Argv {
  explicit Argv(std::vector<std::string> args) : args_(std::move(args)) {
    args_.insert(args_.begin(), "soiq");
    for (std::string& a : args_) pointers_.push_back(a.data());
    pointers_.push_back(nullptr);
  }
  int argc() const { return int(args_.size()); }
  char** argv() { return pointers_.data(); }

 private:
  std::vector<std::string> args_;
  std::vector<char*> pointers_;
};

Status check(const char* command, std::vector<std::string> args) {
  args.insert(args.begin(), command);
  Argv a(args);
  return check_options(*find_command(command), a.argc(), a.argv(), 2);
}

TEST(CheckOptions, AcceptsListedOptionsAndSkipsTheirValues) {
  EXPECT_TRUE(check("query", {"--where", "x>-1", "--select", "-weird", "--desc", "--order-by", "x"}).ok());
  EXPECT_TRUE(check("mesh", {"m.nii", "--label=3", "-o", "out.stl"}).ok());
  EXPECT_TRUE(check("download", {"4", "--output", "x.stl"}).ok());
}

TEST(CheckOptions, RefusesAnUnlistedOptionWithTheClosest) {
  const Status s = check("query", {"--slect", "x"});
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("unknown option '--slect'; did you mean '--select'?"), std::string::npos) << s.message();
}

TEST(CheckOptions, SaysWhenACommandTakesNoOptions) {
  const Status s = check("rm", {"structure", "4", "--force"});
  EXPECT_NE(s.message().find("unknown option '--force' (it takes none)"), std::string::npos) << s.message();
}

TEST(CheckOptions, FindsHelpOnlyWhereAnOptionStands) {
  Argv yes({"query", "--limit", "3", "--help"});
  EXPECT_TRUE(asks_for_help(*find_command("query"), yes.argc(), yes.argv(), 2));
  Argv no({"query", "--select", "--help"});
  EXPECT_FALSE(asks_for_help(*find_command("query"), no.argc(), no.argv(), 2));
  Argv h({"mesh", "-h"});
  EXPECT_TRUE(asks_for_help(*find_command("mesh"), h.argc(), h.argv(), 2));
}

}  // namespace
}  // namespace soiq::cli
