// Regions by name: parse_region accepts inside, shell:R and core:R, and region_name reads back.
#include <gtest/gtest.h>

#include <string>

#include "core/regions/regions.h"

namespace soiq {
namespace {

TEST(Regions, ParseAcceptsTheThreeFormsAndNamesThemBack) {
  for (const char* text : {"inside", "shell:5", "core:2.5"}) {
    auto spec = parse_region(text);
    ASSERT_TRUE(spec.ok()) << text;
    EXPECT_EQ(region_name(*spec), text);
  }
  EXPECT_EQ(parse_region("shell:5")->kind, RegionKind::kShell);
  EXPECT_EQ(parse_region("core:2.5")->radius_mm, 2.5);
}

TEST(Regions, ParseRejectsBadRadiusAndUnknownNames) {
  for (const char* text : {"shell:0", "shell:-1", "core:", "core:2mm", "rim:3", "Inside"}) {
    auto spec = parse_region(text);
    ASSERT_FALSE(spec.ok()) << text;
    EXPECT_EQ(spec.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(spec.status().message().find("expected inside, shell:R or core:R"), std::string::npos);
  }
}

TEST(Regions, AnUnknownNameSuggestsTheClosestWithTheGivenRadius) {
  EXPECT_NE(parse_region("insde").status().message().find("did you mean 'inside'?"), std::string::npos);
  EXPECT_NE(parse_region("shel:5").status().message().find("did you mean 'shell:5'?"), std::string::npos);
  EXPECT_NE(parse_region("cor:2.5").status().message().find("did you mean 'core:2.5'?"), std::string::npos);
  EXPECT_EQ(parse_region("rim:3").status().message().find("did you mean"), std::string::npos);
}

// Found by fuzz_feature_expression: names printed with %g lost digits, so two radii shared one name
// (and soiqd's cache entries). A name now reads back to exactly its radius.
TEST(RegionName, ReadsBackToExactlyItsRadius) {
  for (const double r : {3.0, 2.5, 1.0000001, 0.1, 123456.789, 1e-7}) {
    const RegionSpec shell{RegionKind::kShell, r};
    const auto back = parse_region(region_name(shell));
    ASSERT_TRUE(back.ok()) << region_name(shell) << ": " << back.status().to_string();
    EXPECT_EQ(back->radius_mm, r) << region_name(shell);
  }
  EXPECT_EQ(region_name(RegionSpec{RegionKind::kShell, 3.0}), "shell:3");
  EXPECT_NE(region_name(RegionSpec{RegionKind::kCore, 1.0000001}), region_name(RegionSpec{RegionKind::kCore, 1.0}));
}

}  // namespace
}  // namespace soiq
