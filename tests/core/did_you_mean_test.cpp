#include "core/base/did_you_mean.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace soiq {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(edit_distance("", ""), 0);
  EXPECT_EQ(edit_distance("", "abc"), 3);
  EXPECT_EQ(edit_distance("select", "slect"), 1);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3);
}

TEST(EditDistance, CountsATranspositionOfNeighboursAsOne) {
  EXPECT_EQ(edit_distance("qeury", "query"), 1);
  EXPECT_EQ(edit_distance("ab", "ba"), 1);
}

TEST(ClosestName, SuggestsTheNearestName) {
  const std::vector<std::string> names = {"query", "ls", "rm", "show"};
  EXPECT_EQ(closest_name("qeury", names), "query");
  EXPECT_EQ(did_you_mean("qeury", names), "; did you mean 'query'?");
}

TEST(ClosestName, SuggestsNothingFarOrForShortWords) {
  const std::vector<std::string> names = {"query", "ls", "rm"};
  EXPECT_EQ(closest_name("ms", names), "ls");
  EXPECT_EQ(closest_name("xy", names), "");  // 2 of 2 letters changed is too much to guess
  EXPECT_EQ(closest_name("zzzzzzzz", names), "");
  EXPECT_EQ(did_you_mean("upload", names), "");
}

TEST(ClosestName, IgnoresTheDashesOfOptionsWhenItJudgesLength) {
  const std::vector<std::string> names = {"--select", "--limit"};
  EXPECT_EQ(closest_name("--slect", names), "--select");
  EXPECT_EQ(closest_name("--lmt", names), "");
}

TEST(ClosestName, PrefersTheFirstOfEquals) {
  const std::vector<std::string> names = {"core:R", "shell:R"};
  EXPECT_EQ(closest_name("cor:R", names), "core:R");
}

}  // namespace
}  // namespace soiq
