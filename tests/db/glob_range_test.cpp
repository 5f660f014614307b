#include "db/sql/glob_range.h"

#include <gtest/gtest.h>

namespace soiq::db {
namespace {

TEST(GlobRange, PrefixEndsAtTheFirstWildcard) {
  EXPECT_EQ(glob_range("hippo*").lower, "hippo");
  EXPECT_EQ(glob_range("hippo*").upper, "hippp");
  EXPECT_EQ(glob_range("a?c").lower, "a");
  EXPECT_EQ(glob_range("ab[cd]").lower, "ab");
  EXPECT_EQ(glob_range("exact").upper, "exacu");
}

TEST(GlobRange, LeadingWildcardHasNoRange) {
  EXPECT_EQ(glob_range("*x").lower, "");
  EXPECT_FALSE(glob_range("*x").upper.has_value());
}

TEST(GlobRange, TrailingFfBytesAreDroppedBeforeIncrementing) {
  EXPECT_EQ(glob_range("a\xff\xff*").upper, "b");
  EXPECT_FALSE(glob_range("\xff*").upper.has_value());
}

TEST(GlobRange, AsciiLowerLeavesOtherBytesAlone) { EXPECT_EQ(ascii_lower("HiPPo_L\xc3\x89"), "hippo_l\xc3\x89"); }

TEST(GlobRegex, WildcardsBecomeRegexAndEverythingElseIsLiteral) {
  EXPECT_EQ(glob_regex("hippo*"), "^hippo.*$");
  EXPECT_EQ(glob_regex("a?c"), "^a.c$");
  EXPECT_EQ(glob_regex("a.b+c(d)|e$^{1}\\"), "^a\\.b\\+c\\(d\\)\\|e\\$\\^\\{1\\}\\\\$");
}

TEST(GlobRegex, BracketSetsKeepSQLitesMeaning) {
  EXPECT_EQ(glob_regex("[abc]x"), "^[abc]x$");
  EXPECT_EQ(glob_regex("[^a-z]"), "^[^a-z]$");
  EXPECT_EQ(glob_regex("[]x]"), "^[]x]$");  // a ']' first is a member
  EXPECT_EQ(glob_regex("[^]x]"), "^[^]x]$");
  EXPECT_EQ(glob_regex("[\\[]"), "^[\\\\\\[]$");  // '\' and '[' members escaped for an ARE
  EXPECT_EQ(glob_regex("ab[c"), "a^");            // unterminated: matches nothing, as in SQLite
}

}  // namespace
}  // namespace soiq::db
