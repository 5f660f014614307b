#include "proto/text/feature_expression.h"

#include <gtest/gtest.h>

namespace soiq::proto_text {
namespace {

TEST(ParseFeature, NameAloneIsAShapeFeature) {
  const auto f = parse_feature("voxel_volume_mm3");
  ASSERT_TRUE(f.ok()) << f.status().to_string();
  EXPECT_EQ(f->name(), "voxel_volume_mm3");
  EXPECT_EQ(f->region(), "");
  EXPECT_EQ(f->image(), "");
  EXPECT_FALSE(f->asymmetry());
}

TEST(ParseFeature, RegionAndImageInBrackets) {
  const auto f = parse_feature("mean[shell:5,PT]");
  ASSERT_TRUE(f.ok()) << f.status().to_string();
  EXPECT_EQ(f->name(), "mean");
  EXPECT_EQ(f->region(), "shell:5");
  EXPECT_EQ(f->image(), "PT");
}

TEST(ParseFeature, RegionWithoutImage) {
  const auto f = parse_feature("voxel_count[core:2.5]");
  ASSERT_TRUE(f.ok()) << f.status().to_string();
  EXPECT_EQ(f->region(), "core:2.5");
  EXPECT_EQ(f->image(), "");
}

TEST(ParseFeature, ImageWithoutRegionIsASeriesUidToo) {
  const auto f = parse_feature("mean[,1.2.840.113619.2]");
  ASSERT_TRUE(f.ok()) << f.status().to_string();
  EXPECT_EQ(f->region(), "");
  EXPECT_EQ(f->image(), "1.2.840.113619.2");
}

TEST(ParseFeature, AsymWrapsAFeature) {
  const auto f = parse_feature(" asym( mean[inside,MR] ) ");
  ASSERT_TRUE(f.ok()) << f.status().to_string();
  EXPECT_TRUE(f->asymmetry());
  EXPECT_EQ(f->name(), "mean");
  EXPECT_EQ(f->region(), "inside");
  EXPECT_EQ(f->image(), "MR");
}

TEST(ParseFeature, NameStartingWithAsymIsNotTheFunction) {
  const auto f = parse_feature("asymmetry_score");
  ASSERT_TRUE(f.ok()) << f.status().to_string();
  EXPECT_EQ(f->name(), "asymmetry_score");
  EXPECT_FALSE(f->asymmetry());
}

TEST(ParseFeature, BlanksBetweenTokensAreAllowed) {
  const auto f = parse_feature("mean [ shell:5 , PT ]");
  ASSERT_TRUE(f.ok()) << f.status().to_string();
  EXPECT_EQ(feature_text(*f), "mean[shell:5,PT]");
}

struct BadFeature {
  const char* text;
  const char* phrase;
};

class ParseFeatureError : public testing::TestWithParam<BadFeature> {};

TEST_P(ParseFeatureError, SaysWhatIsWrongAndWhere) {
  const auto f = parse_feature(GetParam().text);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(f.status().message().find(GetParam().phrase), std::string::npos) << f.status().message();
  EXPECT_NE(f.status().message().find("column"), std::string::npos) << f.status().message();
}

INSTANTIATE_TEST_SUITE_P(Malformed, ParseFeatureError,
                         testing::Values(BadFeature{"", "expected a feature name at column 1"},
                                         BadFeature{"1mean", "expected a feature name at column 1"},
                                         BadFeature{"mean[shell:5,PT", "expected ']' at column 16"},
                                         BadFeature{"mean[]", "expected a region"},
                                         BadFeature{"mean[shell:0]", "radius > 0"},
                                         BadFeature{"mean[shell:x]", "radius > 0"},
                                         BadFeature{"mean[around]", "unknown region 'around'"},
                                         BadFeature{"mean[insde]", "did you mean 'inside'?"},
                                         BadFeature{"mean[shel:5]", "did you mean 'shell:5'?"},
                                         BadFeature{"mean[inside,]", "expected an image"},
                                         BadFeature{"asym(voxel_count", "expected ')' closing asym("},
                                         BadFeature{"asym(asym(voxel_count))", "cannot be nested"},
                                         BadFeature{"mean extra", "unexpected text after the feature at column 6"}));

TEST(ParsePredicate, FeatureOperatorNumber) {
  const auto p = parse_predicate("voxel_volume_mm3>50000");
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  EXPECT_EQ(p->feature().name(), "voxel_volume_mm3");
  EXPECT_EQ(p->op(), soiq::v1::GT);
  EXPECT_EQ(p->value(), 50000);
}

TEST(ParsePredicate, TwoCharacterOperatorsAreNotSplit) {
  struct Case {
    const char* text;
    soiq::v1::ComparisonOp op;
  };
  for (const Case& c : {Case{"a <= 1", soiq::v1::LE}, Case{"a >= 1", soiq::v1::GE}, Case{"a == 1", soiq::v1::EQ},
                        Case{"a != 1", soiq::v1::NE}, Case{"a < 1", soiq::v1::LT}, Case{"a > 1", soiq::v1::GT}}) {
    const auto p = parse_predicate(c.text);
    ASSERT_TRUE(p.ok()) << c.text << ": " << p.status().to_string();
    EXPECT_EQ(p->op(), c.op) << c.text;
    EXPECT_STREQ(comparison_text(p->op()), std::string(c.text).substr(2, std::string(c.text).size() - 4).c_str());
  }
}

TEST(ParsePredicate, NumbersMayBeNegativeOrScientific) {
  const auto p = parse_predicate("asym(voxel_volume_mm3) < -0.05");
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  EXPECT_TRUE(p->feature().asymmetry());
  EXPECT_DOUBLE_EQ(p->value(), -0.05);
  const auto q = parse_predicate("mean[shell:5,PT]>=2.5e0 ");
  ASSERT_TRUE(q.ok()) << q.status().to_string();
  EXPECT_DOUBLE_EQ(q->value(), 2.5);
}

TEST(ParsePredicate, MissingOperatorIsNamed) {
  const auto p = parse_predicate("voxel_volume_mm3");
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("expected a comparison"), std::string::npos) << p.status().message();
}

TEST(ParsePredicate, BadNumberIsNamedWithItsColumn) {
  const auto p = parse_predicate("mean[inside,PT] > big");
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(p.status().message().find("expected a number at column 19"), std::string::npos) << p.status().message();
}

TEST(ParsePredicate, SingleEqualsIsNotAnOperator) {
  const auto p = parse_predicate("voxel_count = 3");
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("expected a comparison"), std::string::npos) << p.status().message();
}

TEST(FeatureText, ReadsBackAsTheSameFeature) {
  for (const char* text : {"voxel_count", "mean[shell:5,PT]", "mean[,MR]", "mean[inside]", "asym(mean[core:2,PT])"}) {
    const auto f = parse_feature(text);
    ASSERT_TRUE(f.ok()) << text;
    EXPECT_EQ(feature_text(*f), text);
  }
}

}  // namespace
}  // namespace soiq::proto_text
