// Where a stored structure is converted, on its own: the axis-aligned grid around the stored bounds
// (its margin grown for shells), a series of the study by uid or modality, and the refusals.
#include "server/app/grid_choice.h"

#include <gtest/gtest.h>

#include <cmath>

namespace soiq::server {
namespace {

db::StructureRecord structure_in_box() {
  db::StructureRecord s;
  s.id = 1;
  s.study_uid = "S1";
  const double bounds[6] = {-10, -5, 0, 10, 5, 20};
  for (int i = 0; i < 6; ++i) s.surface.bounds_mm[i] = bounds[i];
  return s;
}

db::SeriesRecord series(const std::string& uid, const std::string& modality, const std::string& sha) {
  db::SeriesRecord r;
  r.series_uid = uid;
  r.study_uid = "S1";
  r.modality = modality;
  r.sha256 = sha;
  r.geometry.dims = {64, 64, 32};
  r.geometry.spacing_mm = {2, 2, 3};
  return r;
}

TEST(GridChoice, TheAxisAlignedGridCoversTheBoundsWithItsMargin) {
  GridChoice c;  // 1 mm, 2 voxels
  Result<ResolvedGrid> g = resolve_grid(c, structure_in_box(), {}, 0, int64_t(1) << 30);
  ASSERT_TRUE(g.ok()) << g.status().to_string();
  const ImageGeometry& geo = g->geometry;
  const double lo[3] = {-10, -5, 0}, hi[3] = {10, 5, 20};
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(geo.spacing_mm[a], 1);
    EXPECT_LE(geo.origin_mm[a], lo[a] - 2 + 1e-9) << a;
    EXPECT_GE(geo.origin_mm[a] + double(geo.dims[a] - 1), hi[a] + 2 - 1e-9) << a;
  }
  EXPECT_EQ(g->key, "axis:1,1,1");
}

TEST(GridChoice, AShellWiderThanTheMarginGrowsIt) {
  GridChoice c;
  Result<ResolvedGrid> plain = resolve_grid(c, structure_in_box(), {}, 0, int64_t(1) << 30);
  Result<ResolvedGrid> shell = resolve_grid(c, structure_in_box(), {}, 5, int64_t(1) << 30);
  ASSERT_TRUE(plain.ok() && shell.ok());
  EXPECT_EQ(shell->geometry.dims[0], plain->geometry.dims[0] + 8);  // ceil(5 / 1) + 1 voxels a side
  // The same voxel centres, the same values (FeatureEngineTest proves it): the same key.
  EXPECT_EQ(shell->key, plain->key);
  // Never less than a voxel of margin, so that the mask's surface closes inside the grid.
  c.margin_voxels = 0;
  Result<ResolvedGrid> bare = resolve_grid(c, structure_in_box(), {}, 0, int64_t(1) << 30);
  ASSERT_TRUE(bare.ok());
  EXPECT_EQ(bare->geometry.dims[0], plain->geometry.dims[0] - 2);
}

TEST(GridChoice, ASeriesIsFoundByUidOrByModalityAndNamedByItsImage) {
  const std::vector<db::SeriesRecord> study = {series("1.1", "MR", "aaa"), series("1.2", "CT", "bbb")};
  GridChoice by_uid;
  by_uid.kind = GridChoice::Kind::kSeriesUid;
  by_uid.series = "1.2";
  Result<ResolvedGrid> g = resolve_grid(by_uid, structure_in_box(), study, 0, int64_t(1) << 30);
  ASSERT_TRUE(g.ok()) << g.status().to_string();
  EXPECT_EQ(g->key, "series:bbb");
  EXPECT_EQ(g->geometry.dims, (std::array<int64_t, 3>{64, 64, 32}));
  GridChoice by_modality;
  by_modality.kind = GridChoice::Kind::kSeriesModality;
  by_modality.series = "mr";  // case-insensitive
  Result<ResolvedGrid> m = resolve_grid(by_modality, structure_in_box(), study, 0, int64_t(1) << 30);
  ASSERT_TRUE(m.ok()) << m.status().to_string();
  EXPECT_EQ(m->key, "series:aaa");
}

TEST(GridChoice, NoSuchSeriesIsNotFoundAndTwoOfAModalityArePrecondition) {
  const std::vector<db::SeriesRecord> study = {series("1.1", "MR", "aaa"), series("1.2", "MR", "bbb")};
  GridChoice c;
  c.kind = GridChoice::Kind::kSeriesModality;
  c.series = "PT";
  EXPECT_EQ(resolve_grid(c, structure_in_box(), study, 0, 1 << 30).status().code(), StatusCode::kNotFound);
  c.series = "MR";
  Result<ResolvedGrid> two = resolve_grid(c, structure_in_box(), study, 0, 1 << 30);
  EXPECT_EQ(two.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(two.status().message().find("series uid"), std::string::npos) << two.status().message();
}

TEST(GridChoice, AGridOverTheVoxelLimitIsResourceExhaustedBeforeAnythingIsAllocated) {
  GridChoice fine;
  fine.spacing_mm = {0.01, 0.01, 0.01};
  Result<ResolvedGrid> g = resolve_grid(fine, structure_in_box(), {}, 0, 500'000'000);
  EXPECT_EQ(g.status().code(), StatusCode::kResourceExhausted);
}

}  // namespace
}  // namespace soiq::server
