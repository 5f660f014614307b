#include "client/cli/query_args.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace soiq::cli {
namespace {

Result<QueryArgs> parse(std::vector<std::string> args) {
  args.insert(args.begin(), "query");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  return parse_query_args(int(args.size()), argv.data());
}

TEST(ParseQueryArgs, Stage1FlagsFillTheFilter) {
  const auto a = parse(
      {"--patient",         "STS_*",    "--sex",           "F",       "--min-age",     "50",      "--max-age", "80",
       "--study-date-from", "20150101", "--modality",      "MR",      "--description", "*brain*", "--name",    "hippo*",
       "--laterality",      "L",        "--birth-date-to", "19700101"});
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  const soiq::v1::Stage1Filter& s = a->request.stage1();
  EXPECT_EQ(s.patient_id_glob(), "STS_*");
  EXPECT_EQ(s.sex(), "F");
  EXPECT_EQ(s.min_age_years(), 50);
  EXPECT_EQ(s.max_age_years(), 80);
  EXPECT_EQ(s.study_date_from(), "20150101");
  EXPECT_EQ(s.birth_date_to(), "19700101");
  EXPECT_EQ(s.modality(), "MR");
  EXPECT_EQ(s.study_description_glob(), "*brain*");
  EXPECT_EQ(s.structure_name_glob(), "hippo*");
  EXPECT_EQ(s.laterality(), "L");
  EXPECT_FALSE(a->request.stage1().has_min_age_years() == false);
}

TEST(ParseQueryArgs, AgesAreUnsetWhenNotGiven) {
  const auto a = parse({});
  ASSERT_TRUE(a.ok());
  EXPECT_FALSE(a->request.stage1().has_min_age_years());
  EXPECT_FALSE(a->request.stage1().has_max_age_years());
  EXPECT_FALSE(a->request.has_order_by());
  EXPECT_FALSE(a->request.has_grid());
}

TEST(ParseQueryArgs, WhereSelectOrderByAndColumnsInTheServersOrder) {
  const auto a =
      parse({"--where", "voxel_volume_mm3>50000", "--select", "sphericity", "--where", "mean[shell:5,PT]>2.5",
             "--order-by", "mean[inside,PT]", "--desc", "--limit", "10", "--series-modality", "PT", "--format", "csv"});
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  const soiq::v1::QueryRequest& r = a->request;
  ASSERT_EQ(r.where_size(), 2);
  EXPECT_EQ(r.where(1).feature().region(), "shell:5");
  EXPECT_EQ(r.where(1).op(), soiq::v1::GT);
  EXPECT_TRUE(r.descending());
  EXPECT_EQ(r.limit(), 10);
  EXPECT_EQ(r.grid().series_modality(), "PT");
  EXPECT_EQ(a->format, "csv");
  EXPECT_EQ(query_feature_columns(r),
            (std::vector<std::string>{"voxel_volume_mm3", "mean[shell:5,PT]", "sphericity", "mean[inside,PT]"}));
}

TEST(DistinctColumns, RepeatedFeatureIsShownOnce) {
  EXPECT_EQ(distinct_columns({"a", "b", "a", "c", "b"}), (std::vector<size_t>{0, 1, 3}));
}

TEST(ParseQueryArgs, SpacingGivesAnAxisAlignedGrid) {
  const auto a = parse({"--spacing", "0.5", "--margin", "3"});
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  EXPECT_EQ(a->request.grid().spacing_mm(), 0.5);
  EXPECT_EQ(a->request.grid().margin_voxels(), 3);
}

struct BadQuery {
  std::vector<std::string> args;
  const char* phrase;
};

class ParseQueryArgsError : public testing::TestWithParam<BadQuery> {};

TEST_P(ParseQueryArgsError, IsInvalidArgumentWithAPhrase) {
  const auto a = parse(GetParam().args);
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(a.status().message().find(GetParam().phrase), std::string::npos) << a.status().message();
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, ParseQueryArgsError,
    testing::Values(BadQuery{{"--where", "mean[shell:5,PT>2"}, "--where: expected ']' at column 16"},
                    BadQuery{{"--order-by", "mean >"}, "--order-by: unexpected text"},
                    BadQuery{{"--desc"}, "--desc needs --order-by"},
                    BadQuery{{"--sex", "X"}, "--sex must be M, F or O"},
                    BadQuery{{"--study-date-from", "2015"}, "YYYYMMDD"},
                    BadQuery{{"--min-age", "old"}, "--min-age must be a number"},
                    BadQuery{{"--limit", "0"}, "--limit must be a whole number"},
                    BadQuery{{"--spacing", "1", "--series-modality", "PT"}, "either --spacing or --series-modality"},
                    BadQuery{{"--series", "1.2.3"}, "unknown option '--series'"},
                    BadQuery{{"--format", "xml"}, "--format must be table, json or csv"},
                    BadQuery{{"volume>3"}, "conditions go in --where"},
                    BadQuery{{"--where"}, "--where needs a value"}));

TEST(InCommandLineWords, NamesTheFlagAndTheExpressionInsteadOfTheField) {
  const auto a = parse({"--where", "volume_mm3 > 5", "--select", "mean[inside,PT]", "--order-by", "sphericity"});
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  const Status where = in_command_line_words(invalid_argument("where[0]: unknown feature 'volume_mm3'"), a->request);
  EXPECT_EQ(where.message(), "--where 'volume_mm3 > 5': unknown feature 'volume_mm3'");
  EXPECT_EQ(where.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(in_command_line_words(invalid_argument("select[0]: needs an image"), a->request).message(),
            "--select 'mean[inside,PT]': needs an image");
  EXPECT_EQ(in_command_line_words(invalid_argument("order_by: an array"), a->request).message(),
            "--order-by 'sphericity': an array");
  EXPECT_EQ(in_command_line_words(not_found("where[7]: out of range"), a->request).message(), "where[7]: out of range");
  EXPECT_EQ(in_command_line_words(Status(StatusCode::kUnavailable, "no server"), a->request).message(), "no server");
}

}  // namespace
}  // namespace soiq::cli
