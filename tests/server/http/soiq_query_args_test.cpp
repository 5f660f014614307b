// GET /soiq/v1/query's arguments as a QueryRequest (server/http/soiq_query_args.h): soiq query's
// options by name, each checked for form, and what is refused.
#include "server/http/soiq_query_args.h"

#include <gtest/gtest.h>

#include "tests/support/shared_cases.h"

namespace soiq::server::http {
namespace {

using Args = std::vector<std::pair<std::string, std::string>>;

TEST(SoiqQueryArgs, TheCommandLinesOptionsByName) {
  Result<v1::QueryRequest> r = parse_soiq_query_args({{"patient", "STS_*"},
                                                      {"min-age", "40.5"},
                                                      {"study-date-to", "20201231"},
                                                      {"name", "GTV*"},
                                                      {"where", "voxel_volume_mm3 > 1000"},
                                                      {"where", "mean[shell:5,PT] >= 2.5"},
                                                      {"select", "sphericity"},
                                                      {"order-by", "asym(voxel_volume_mm3)"},
                                                      {"desc", "true"},
                                                      {"limit", "7"},
                                                      {"spacing", "1,1,2"},
                                                      {"margin", "3"},
                                                      {"interpolation", "linear"}});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->stage1().patient_id_glob(), "STS_*");
  EXPECT_EQ(r->stage1().min_age_years(), 40.5);
  EXPECT_EQ(r->stage1().study_date_to(), "20201231");
  EXPECT_EQ(r->stage1().structure_name_glob(), "GTV*");
  ASSERT_EQ(r->where_size(), 2);
  EXPECT_EQ(r->where(1).feature().region(), "shell:5");
  EXPECT_EQ(r->where(1).value(), 2.5);
  EXPECT_EQ(r->select(0).name(), "sphericity");
  EXPECT_TRUE(r->order_by().asymmetry());
  EXPECT_TRUE(r->descending());
  EXPECT_EQ(r->limit(), 7);
  EXPECT_EQ(r->grid().spacing_xyz().z(), 2);
  EXPECT_EQ(r->grid().margin_voxels(), 3);
  EXPECT_EQ(r->interpolation(), v1::LINEAR);
}

TEST(SoiqQueryArgs, TheSharedCasesAsTheOtherFaces) {
  const auto cases = soiq::testing::shared_cases("query_options.json");
  for (const auto& c : cases.at("accepted")) {
    Result<v1::QueryRequest> r = parse_soiq_query_args(soiq::testing::query_args_of(c));
    ASSERT_TRUE(r.ok()) << c.dump() << ": " << r.status().message();
    EXPECT_TRUE(soiq::testing::same_message(c.at("request"), *r)) << c.dump();
  }
  for (const auto& c : cases.at("refused")) {
    Result<v1::QueryRequest> r = parse_soiq_query_args(soiq::testing::query_args_of(c));
    ASSERT_FALSE(r.ok()) << c.dump();
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find(c.at("option").get<std::string>()), std::string::npos) << r.status().message();
  }
}

TEST(SoiqQueryArgs, RefusalsNameTheArgumentWithoutDashes) {
  const std::vector<std::pair<Args, std::string>> cases = {
      {{{"nmae", "x"}}, "unknown option 'nmae'; did you mean 'name'?"},
      {{{"name", "a"}, {"name", "b"}}, "name is given twice"},
      {{{"where", "sphericity >> 1"}}, "where 'sphericity >> 1': expected a number at column 13"},
      {{{"desc", "true"}}, "desc needs order-by"},
      {{{"margin", "2"}}, "margin goes with spacing"},
  };
  for (const auto& [args, text] : cases) {
    Result<v1::QueryRequest> r = parse_soiq_query_args(args);
    ASSERT_FALSE(r.ok()) << text;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find(text), std::string::npos) << r.status().message();
  }
}

TEST(SoiqQueryArgs, ABareDescIsTrue) {
  Result<v1::QueryRequest> r = parse_soiq_query_args({{"order-by", "sphericity"}, {"desc", ""}});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_TRUE(r->descending());
}

}  // namespace
}  // namespace soiq::server::http
