// Regions around and within a structure: the error paths of region(), each with its code and a key
// phrase of its message.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/regions/regions.h"
#include "tests/core/regions_blob.h"

namespace soiq {
namespace {

using testing::random_blob;

TEST(Regions, NonPositiveRadiusIsInvalidArgument) {
  const RunLengthVolume v = from_mask(random_blob(5));
  for (double r : {0.0, -2.0, std::nan("")}) {
    for (RegionKind kind : {RegionKind::kShell, RegionKind::kCore}) {
      auto got = region(v, {kind, r});
      ASSERT_FALSE(got.ok());
      EXPECT_EQ(got.status().code(), StatusCode::kInvalidArgument);
      EXPECT_NE(got.status().message().find("radius must be"), std::string::npos) << got.status().message();
    }
  }
}

TEST(Regions, GrownBoxOverTheLimitIsResourceExhausted) {
  for (const RegionMethod method : {RegionMethod::kCheapest, RegionMethod::kRuns, RegionMethod::kTransform}) {
    auto got = region(from_mask(random_blob(6)), {RegionKind::kShell, 2.0}, {.max_box_voxels = 100, .method = method});
    ASSERT_FALSE(got.ok());
    EXPECT_EQ(got.status().code(), StatusCode::kResourceExhausted);
    EXPECT_NE(got.status().message().find("over the limit"), std::string::npos) << got.status().message();
  }
}

TEST(Regions, RunOutsideTheGridIsInvalidArgument) {
  RunLengthVolume v = from_mask(random_blob(7));
  ASSERT_FALSE(v.runs.empty());
  v.runs.back().end = 27;  // the grid has 26 voxels along i
  auto got = region(v, {RegionKind::kShell, 2.0});
  ASSERT_FALSE(got.ok());
  EXPECT_EQ(got.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(got.status().message().find("run table"), std::string::npos) << got.status().message();
}

}  // namespace
}  // namespace soiq
