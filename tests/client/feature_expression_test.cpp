// The feature grammar (proto/text/feature_expression.h) against the shared cases
// (tests/data/shared_cases/feature_expressions.json), which the Python client is held to as well:
// the same texts accepted as the same messages with the same canonical text, the same texts refused
// at the same column.
#include "proto/text/feature_expression.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "tests/support/shared_cases.h"

namespace soiq::proto_text {
namespace {

using soiq::testing::same_message;
using soiq::testing::shared_cases;

std::string predicate_text(const soiq::v1::Predicate& p) {
  char value[32];
  std::snprintf(value, sizeof value, "%g", p.value());
  return feature_text(p.feature()) + " " + comparison_text(p.op()) + " " + value;
}

template <typename Parse, typename Text>
void check_cases(const char* kind, const char* message_key, Parse parse, Text text_of) {
  int accepted = 0, refused = 0;
  const nlohmann::json cases = shared_cases("feature_expressions.json");
  for (const auto& c : cases.at(kind)) {
    const std::string text = c.at("text");
    const auto got = parse(text);
    if (c.contains("error")) {
      ++refused;
      ASSERT_FALSE(got.ok()) << "'" << text << "' was accepted";
      EXPECT_EQ(got.status().code(), StatusCode::kInvalidArgument);
      const std::string& m = got.status().message();
      EXPECT_NE(m.find(c.at("error").get<std::string>()), std::string::npos) << text << ": " << m;
      const std::string column = "at column " + std::to_string(c.at("column").get<int>()) + " of";
      EXPECT_NE(m.find(column), std::string::npos) << text << ": " << m;
      continue;
    }
    ++accepted;
    ASSERT_TRUE(got.ok()) << text << ": " << got.status().message();
    EXPECT_TRUE(same_message(c.at(message_key), *got)) << text;
    EXPECT_EQ(text_of(*got), c.at("canonical").get<std::string>()) << text;
    // The canonical text reads back as the same message.
    const auto again = parse(text_of(*got));
    ASSERT_TRUE(again.ok()) << text_of(*got);
    EXPECT_TRUE(same_message(c.at(message_key), *again)) << text_of(*got);
  }
  EXPECT_GT(accepted, 5);
  EXPECT_GT(refused, 5);
}

TEST(FeatureGrammar, FeaturesAsTheSharedCasesSay) { check_cases("features", "feature", parse_feature, feature_text); }

TEST(FeatureGrammar, PredicatesAsTheSharedCasesSay) {
  check_cases("predicates", "predicate", parse_predicate, predicate_text);
}

TEST(FeatureGrammar, EveryComparisonHasOneSymbolBothWays) {
  for (const Comparison c : kComparisons) {
    const soiq::v1::ComparisonOp op = proto_comparison(c);
    EXPECT_NE(op, soiq::v1::COMPARISON_OP_UNSPECIFIED);
    EXPECT_EQ(comparison_of(op), c);
    EXPECT_EQ(comparison_of_symbol(comparison_symbol(c)), c);
    const auto p = parse_predicate(std::string("a ") + comparison_symbol(c) + " 1");
    ASSERT_TRUE(p.ok()) << comparison_symbol(c);
    EXPECT_EQ(p->op(), op);
  }
  EXPECT_EQ(comparison_of(soiq::v1::COMPARISON_OP_UNSPECIFIED), std::nullopt);
  EXPECT_STREQ(comparison_text(soiq::v1::COMPARISON_OP_UNSPECIFIED), "?");
  EXPECT_EQ(comparison_of_symbol("="), std::nullopt);
  EXPECT_STREQ(sql_operator(Comparison::kNotEqual), "<>");
  EXPECT_STREQ(sql_operator(Comparison::kEqual), "=");
}

}  // namespace
}  // namespace soiq::proto_text
