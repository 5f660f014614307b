// The Convert and ComputeFeatures engines on their own, without gRPC: a box in a real SQLite
// store, converted on the pool under the memory budget (its voxels against a count of the grid's
// centres strictly inside the box), exported as a NIfTI mask that reads back to the same voxels,
// and its features computed once and then read from the cache.
#include "server/app/structure_conversion.h"

#include <gtest/gtest.h>

#include "core/base/run_length_volume.h"
#include "core/geometry/primitives.h"
#include "core/io/read_image.h"
#include "server/app/stored_structure_features.h"
#include "tests/db/temp_store.h"
#include "tests/server/stored_box.h"

namespace soiq::server {
namespace {

using db::testing::TempDir;

// Chosen so that no voxel centre of a 1 mm grid lies on a face, whatever the grid's origin
// (the test checks it), so "inside" is plain.
constexpr double kLo[3] = {0.25, 0.35, 0.45}, kHi[3] = {10.6, 5.7, 3.8};

class StructureConversionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    id_ = testing::add_stored_box(*store_, {kLo[0], kLo[1], kLo[2]}, {kHi[0], kHi[1], kHi[2]}, "box");
    ASSERT_GT(id_, 0);
  }

  // The centres of `g` strictly inside the box; fails the test if one lies on a face.
  static int64_t centres_inside(const ImageGeometry& g) {
    int64_t n = 0;
    for (int k = 0; k < g.dims[2]; ++k)
      for (int j = 0; j < g.dims[1]; ++j)
        for (int i = 0; i < g.dims[0]; ++i) {
          const int idx[3] = {i, j, k};
          bool inside = true;
          for (int a = 0; a < 3; ++a) {
            const double x = g.origin_mm[a] + g.spacing_mm[a] * idx[a];  // the grid is axis-aligned
            EXPECT_TRUE(x != kLo[a] && x != kHi[a]) << "a centre on a face makes the oracle ambiguous";
            inside = inside && x > kLo[a] && x < kHi[a];
          }
          n += inside;
        }
    return n;
  }

  TempDir tmp_;
  std::unique_ptr<db::SqliteStore> store_ = db::testing::open_store(tmp_.file("soiq.db"));
  MemoryBudget budget_{int64_t(1) << 30};
  FeatureEngine features_{*store_, int64_t(1) << 26, budget_};
  WorkerPool pool_{2};
  int64_t id_ = 0;
  std::function<Status()> never_stop_ = [] { return ok_status(); };
};

TEST_F(StructureConversionTest, TheVolumeIsEveryCentreInsideAndIsAccountedUntilReleased) {
  Result<StructureConversion> c =
      convert_structure(*store_, features_, pool_, id_, GridChoice{}, FillRule::kNonZero, false, never_stop_);
  ASSERT_TRUE(c.ok()) << c.status().to_string();
  EXPECT_EQ(c->structure.id, id_);
  EXPECT_EQ(voxel_count(c->voxelization.volume), centres_inside(c->grid.geometry));
  EXPECT_GT(voxel_count(c->voxelization.volume), 0);
  EXPECT_GT(c->held.bytes(), 0);
  EXPECT_EQ(budget_.in_use(), c->held.bytes());
  c = Status(StatusCode::kCancelled, "dropped");
  EXPECT_EQ(budget_.in_use(), 0);
}

TEST_F(StructureConversionTest, TheMaskReadsBackToTheSameVoxels) {
  Result<StructureConversion> c =
      convert_structure(*store_, features_, pool_, id_, GridChoice{}, FillRule::kNonZero, true, never_stop_);
  ASSERT_TRUE(c.ok()) << c.status().to_string();
  Result<std::string> bytes = mask_nifti_bytes(c->voxelization.volume, int64_t(1) << 26);
  ASSERT_TRUE(bytes.ok()) << bytes.status().to_string();
  Result<Image> mask = decode_image(*bytes, "nii", "mask");
  ASSERT_TRUE(mask.ok()) << mask.status().to_string();
  EXPECT_EQ(mask->geometry.dims, c->grid.geometry.dims);
  int64_t ones = 0;
  for (float v : mask->voxels) ones += v == 1.0f;
  EXPECT_EQ(ones, voxel_count(c->voxelization.volume));
}

TEST_F(StructureConversionTest, AnUnknownStructureIsNotFound) {
  Result<StructureConversion> c =
      convert_structure(*store_, features_, pool_, id_ + 99, GridChoice{}, FillRule::kNonZero, false, never_stop_);
  EXPECT_EQ(c.status().code(), StatusCode::kNotFound);
}

TEST_F(StructureConversionTest, WorkThatCanNeverFitTheBudgetIsRefusedAndHoldsNothing) {
  MemoryBudget tiny(1024);
  FeatureEngine engine(*store_, int64_t(1) << 26, tiny);
  Result<StructureConversion> c =
      convert_structure(*store_, engine, pool_, id_, GridChoice{}, FillRule::kNonZero, false, never_stop_);
  EXPECT_EQ(c.status().code(), StatusCode::kResourceExhausted);
  EXPECT_NE(c.status().message().find("--memory-budget"), std::string::npos) << c.status().message();
  EXPECT_EQ(tiny.in_use(), 0);
}

TEST_F(StructureConversionTest, FeaturesAreComputedOnceThenReadFromTheCache) {
  FeatureAsk ask;
  ask.names = {"mesh_volume_mm3", "voxel_count"};
  ASSERT_TRUE(complete_feature_ask(ask).ok());
  Result<StoredStructureFeatures> first = stored_structure_features(*store_, features_, pool_, id_, ask);
  ASSERT_TRUE(first.ok()) << first.status().to_string();
  EXPECT_FALSE(first->from_cache);
  Result<StoredStructureFeatures> second = stored_structure_features(*store_, features_, pool_, id_, ask);
  ASSERT_TRUE(second.ok()) << second.status().to_string();
  EXPECT_TRUE(second->from_cache);
  EXPECT_EQ(second->compute_ms, 0);
  ASSERT_EQ(first->plan.wants.size(), 2u);
  const double volume = (kHi[0] - kLo[0]) * (kHi[1] - kLo[1]) * (kHi[2] - kLo[2]);
  EXPECT_NEAR(second->values.at(first->plan.wants[0].entry).at(0), volume, 1e-9 * volume);
  for (const WantedValue& w : first->plan.wants) EXPECT_EQ(first->values.at(w.entry), second->values.at(w.entry));
  Result<StructureConversion> c =
      convert_structure(*store_, features_, pool_, id_, GridChoice{}, FillRule::kNonZero, false, never_stop_);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(second->values.at(first->plan.wants[1].entry).at(0), double(voxel_count(c->voxelization.volume)));
}

}  // namespace
}  // namespace soiq::server
