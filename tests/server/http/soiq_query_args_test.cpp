// GET /soiq/v1/query's arguments as a QueryRequest (server/http/soiq_query_args.h): soiq query's
// options by name, each checked for form, and what is refused.
#include "server/http/soiq_query_args.h"

#include <gtest/gtest.h>

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

TEST(SoiqQueryArgs, RefusalsNameTheArgument) {
  const std::vector<std::pair<Args, std::string>> cases = {
      {{{"nmae", "x"}}, "did you mean 'name'"},
      {{{"name", "a"}, {"name", "b"}}, "given twice"},
      {{{"min-age", "old"}}, "min-age must be a number"},
      {{{"limit", "0"}}, "limit must be an integer"},
      {{{"where", "sphericity >> 1"}}, "where='sphericity >> 1'"},
      {{{"desc", "true"}}, "desc needs order-by"},
      {{{"margin", "2"}}, "margin goes with spacing"},
      {{{"spacing", "1,2"}}, "spacing is S or SX,SY,SZ"},
      {{{"spacing", "-1"}}, "spacing must be > 0"},
      {{{"spacing", "1"}, {"series-modality", "CT"}}, "not both"},
      {{{"interpolation", "cubic"}}, "nearest or linear"},
  };
  for (const auto& [args, text] : cases) {
    Result<v1::QueryRequest> r = parse_soiq_query_args(args);
    ASSERT_FALSE(r.ok()) << text;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find(text), std::string::npos) << r.status().message();
  }
}

}  // namespace
}  // namespace soiq::server::http
