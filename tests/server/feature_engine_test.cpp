// The feature engine on its own, without gRPC: asks completed and checked against the catalogue,
// plans that name their cache entries without decoding anything, and computations on a real
// SQLite store of a box and a constant image whose values are known by hand: the box's centres
// inside on the image's 1 mm grid are counted, the mean of a constant is the constant, and its
// centre of mass shift is zero. Cached after computing; refused over the budget, the voxel limit
// or after a cancel.
#include "server/app/feature_engine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <type_traits>

#include "core/features/feature_catalogue.h"
#include "db/image_blob.h"
#include "tests/db/temp_store.h"
#include "tests/server/stored_box.h"

namespace soiq::server {
namespace {

using db::testing::contains;
using db::testing::TempDir;

// No centre of the image's grid (integers from -1) lies on a face: inside are x 1..10, y 1..5,
// z 1..3, so 10 x 5 x 3 = 150 centres.
constexpr double kLo[3] = {0.25, 0.35, 0.45}, kHi[3] = {10.6, 5.7, 3.8};
constexpr int64_t kInsideOnImageGrid = 150;
constexpr float kImageValue = 7;

FeatureAsk ask_of(std::vector<std::string> names, std::vector<std::string> images = {}) {
  FeatureAsk ask;
  ask.names = std::move(names);
  ask.images = std::move(images);
  return ask;
}

TEST(CompleteFeatureAsk, NoNamesAskEveryShapeFeatureOnTheInsideRegion) {
  FeatureAsk ask;
  ASSERT_TRUE(complete_feature_ask(ask).ok());
  EXPECT_EQ(ask.names, shape_feature_names());
  ASSERT_EQ(ask.regions.size(), 1u);
  EXPECT_EQ(region_name(ask.regions[0]), region_name(RegionSpec{}));
}

TEST(CompleteFeatureAsk, AnUnknownNameIsRefusedWithTheKnownOnes) {
  FeatureAsk ask = ask_of({"sphericty"});
  const Status s = complete_feature_ask(ask);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(s.message(), "unknown feature 'sphericty'")) << s.message();
  EXPECT_TRUE(contains(s.message(), "sphericity")) << s.message();
}

TEST(CompleteFeatureAsk, AnIntensityFeatureNeedsAnImage) {
  FeatureAsk ask = ask_of({"mean"});
  const Status s = complete_feature_ask(ask);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(s.message(), "need an image")) << s.message();
}

TEST(CompleteFeatureAsk, AnImageNeedsAnIntensityFeatureButVoxelCountTakesOne) {
  FeatureAsk shape_only = ask_of({"sphericity"}, {"PT"});
  EXPECT_EQ(complete_feature_ask(shape_only).code(), StatusCode::kInvalidArgument);
  FeatureAsk voxels = ask_of({"voxel_count"}, {"PT"});
  EXPECT_TRUE(complete_feature_ask(voxels).ok());
}

TEST(CompleteFeatureAsk, ARegionAskedTwiceIsKeptOnce) {
  FeatureAsk ask = ask_of({"mean"}, {"PT"});
  RegionSpec shell;
  shell.kind = RegionKind::kShell;
  shell.radius_mm = 2;
  ask.regions = {shell, RegionSpec{}, shell};
  ASSERT_TRUE(complete_feature_ask(ask).ok());
  ASSERT_EQ(ask.regions.size(), 2u);
  EXPECT_EQ(region_name(ask.regions[0]), region_name(shell));
}

TEST(FeatureEntry, AShapeEntryIsItsNameAndAnIntensityEntryCarriesRegionImageAndInterpolation) {
  EXPECT_EQ(feature_entry("sphericity", "", "", Interpolation::kLinear), "sphericity");
  EXPECT_EQ(feature_entry("mean", "inside", "abc", Interpolation::kNearest),
            "mean|inside|abc|" + std::string(interpolation_name(Interpolation::kNearest)));
}

class FeatureEngineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    id_ = testing::add_stored_box(*store_, {kLo[0], kLo[1], kLo[2]}, {kHi[0], kHi[1], kHi[2]}, "box");
    ASSERT_GT(id_, 0);
    add_series("1.2.840.1", "PT", std::vector<float>(14 * 10 * 8, kImageValue));
  }

  // An image of the box's study on the 1 mm grid of 14 x 10 x 8 voxels from (-1, -1, -1).
  void add_series(const std::string& uid, const std::string& modality, std::vector<float> voxels) {
    db::NewSeries s;
    s.patient.patient_id = "P1";
    s.study.study_uid = "S1";
    s.series.series_uid = uid;
    s.series.study_uid = "S1";
    s.series.modality = modality;
    Image image;
    image.geometry.dims = {14, 10, 8};
    image.geometry.origin_mm = {-1, -1, -1};
    image.voxels = std::move(voxels);
    s.series.geometry = image.geometry;
    Result<db::EncodedImage> encoded = db::encode_image(image);
    ASSERT_TRUE(encoded.ok()) << encoded.status().to_string();
    s.series.sha256 = encoded->sha256;
    s.image_blob = encoded->blob;
    ASSERT_TRUE(store_->put_series(std::move(s)).ok());
  }

  Result<FeaturePlan> plan(FeatureAsk& ask) {
    SOIQ_RETURN_IF_ERROR(complete_feature_ask(ask));
    SOIQ_ASSIGN_OR_RETURN(const db::StructureRecord structure, store_->get_structure(id_));
    SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, store_->list_series("S1"));
    return features_.plan(structure, series, ask);
  }

  static GridChoice on_pt() {
    GridChoice g;
    g.kind = GridChoice::Kind::kSeriesModality;
    g.series = "PT";
    return g;
  }

  TempDir tmp_;
  std::unique_ptr<db::SqliteStore> store_ = db::testing::open_store(tmp_.file("soiq.db"));
  MemoryBudget budget_{int64_t(1) << 30};
  FeatureEngine features_{*store_, int64_t(1) << 26, budget_};
  int64_t id_ = 0;
};

TEST_F(FeatureEngineTest, APlanWantsVoxelCountOfTheStructureAndOfEachRegionOnTheImage) {
  FeatureAsk ask = ask_of({"voxel_count"}, {"PT"});
  Result<FeaturePlan> p = plan(ask);
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  ASSERT_EQ(p->wants.size(), 2u);
  EXPECT_EQ(p->wants[0].entry, "voxel_count");
  EXPECT_EQ(p->wants[1].region, "inside");
  EXPECT_EQ(p->wants[1].image, "PT");
  ASSERT_EQ(p->images.size(), 1u);
  EXPECT_EQ(p->wants[1].entry, feature_entry("voxel_count", "inside", p->images[0].sha256, ask.interpolation));
  const std::string version_and_surface =
      "v" + std::to_string(feature_definitions_version()) + "|" + p->structure.surface.sha256 + "|";
  EXPECT_EQ(p->cache_key.substr(0, version_and_surface.size()), version_and_surface);
}

TEST_F(FeatureEngineTest, ASeriesNamedByModalityAndByUidIsPlannedOnce) {
  FeatureAsk ask = ask_of({"mean"}, {"PT", "1.2.840.1"});
  Result<FeaturePlan> p = plan(ask);
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  ASSERT_EQ(p->images.size(), 1u);
  ASSERT_EQ(p->wants.size(), 1u);
  EXPECT_EQ(p->wants[0].image, "PT");
}

TEST_F(FeatureEngineTest, AnImageTheStudyDoesNotHaveIsNotFound) {
  FeatureAsk ask = ask_of({"mean"}, {"CT"});
  EXPECT_EQ(plan(ask).status().code(), StatusCode::kNotFound);
}

TEST_F(FeatureEngineTest, ValuesOnTheImageGridAreTheHandCountAndAreCached) {
  FeatureAsk ask = ask_of({"voxel_count", "mean", "centre_of_mass_shift_mm"}, {"PT"});
  ask.grid = on_pt();
  Result<FeaturePlan> p = plan(ask);
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  Result<FeatureValues> v = features_.compute(*p, ask);
  ASSERT_TRUE(v.ok()) << v.status().to_string();
  const std::string sha = p->images[0].sha256;
  EXPECT_EQ(v->at("voxel_count").at(0), double(kInsideOnImageGrid));
  EXPECT_EQ(v->at(feature_entry("voxel_count", "inside", sha, ask.interpolation)).at(0), double(kInsideOnImageGrid));
  EXPECT_EQ(v->at(feature_entry("mean", "inside", sha, ask.interpolation)).at(0), kImageValue);
  EXPECT_EQ(v->at(feature_entry("centre_of_mass_shift_mm", "inside", sha, ask.interpolation)).at(0), 0);
  Result<std::vector<db::CachedFeature>> cached = store_->cached_features({p->cache_key});
  ASSERT_TRUE(cached.ok()) << cached.status().to_string();
  for (const WantedValue& w : p->wants) {
    const bool stored =
        std::any_of(cached->begin(), cached->end(), [&](const db::CachedFeature& c) { return c.entry == w.entry; });
    EXPECT_TRUE(stored) << w.entry;
  }
  EXPECT_EQ(budget_.in_use(), 0);
}

// Why an axis-aligned grid's cache key leaves out its margin (grid_choice.h): on a grid with a wider
// margin, every shape value and every intensity value of every region, on an image that varies
// everywhere, is bitwise the same.
TEST_F(FeatureEngineTest, AnAxisAlignedGridsMarginChangesNoValueAndNotTheCacheKey) {
  std::vector<float> varying;
  for (int64_t i = 0; i < 14 * 10 * 8; ++i) varying.push_back(float((i * 7919) % 1000) / 7.0f);
  add_series("1.2.840.2", "MR", varying);

  std::vector<std::string> names = shape_feature_names();
  for (const char* n : {"mean", "minimum", "maximum", "median", "p90", "voxel_count"}) names.emplace_back(n);
  FeatureAsk narrow = ask_of(names, {"MR"});
  narrow.regions = {RegionSpec{}, RegionSpec{RegionKind::kShell, 2}, RegionSpec{RegionKind::kCore, 1}};
  FeatureAsk wide = narrow;
  wide.grid.margin_voxels = 9;
  Result<FeaturePlan> a = plan(narrow);
  Result<FeaturePlan> b = plan(wide);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_NE(a->grid.geometry.dims, b->grid.geometry.dims);
  EXPECT_EQ(a->cache_key, b->cache_key);
  Result<FeatureValues> va = features_.compute(*a, narrow);
  Result<FeatureValues> vb = features_.compute(*b, wide);
  ASSERT_TRUE(va.ok()) << va.status().to_string();
  ASSERT_TRUE(vb.ok()) << vb.status().to_string();
  ASSERT_EQ(va->size(), vb->size());
  for (const auto& [entry, value] : *va) {
    ASSERT_TRUE(vb->count(entry)) << entry;
    EXPECT_EQ(value, vb->at(entry)) << entry;  // bitwise: the same samples in the same order
  }
}

TEST_F(FeatureEngineTest, TheCentreOfMassShiftOnAnotherGridIsAFailedPrecondition) {
  FeatureAsk ask = ask_of({"centre_of_mass_shift_mm"}, {"PT"});  // on an axis-aligned grid
  Result<FeaturePlan> p = plan(ask);
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  Result<FeatureValues> v = features_.compute(*p, ask);
  EXPECT_EQ(v.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(v.status().message(), "structure's own grid")) << v.status().message();
}

TEST_F(FeatureEngineTest, ACancelledComputationStopsAndCachesNothing) {
  FeatureAsk ask = ask_of({"voxel_count"});
  Result<FeaturePlan> p = plan(ask);
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  const std::atomic<bool> cancelled{true};
  EXPECT_EQ(features_.compute(*p, ask, &cancelled).status().code(), StatusCode::kCancelled);
  EXPECT_EQ(store_->counts()->cached_features, 0);
}

TEST_F(FeatureEngineTest, WorkThatCanNeverFitTheBudgetIsRefusedNamingTheStructure) {
  MemoryBudget tiny(1024);
  FeatureEngine engine(*store_, int64_t(1) << 26, tiny);
  FeatureAsk ask = ask_of({"voxel_count"});
  Result<FeaturePlan> p = plan(ask);
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  Result<FeatureEngine::Admission> held = engine.admit(p->structure, p->grid.geometry, {});
  EXPECT_EQ(held.status().code(), StatusCode::kResourceExhausted);
  EXPECT_TRUE(contains(held.status().message(), "structure " + std::to_string(id_))) << held.status().message();
  EXPECT_EQ(tiny.in_use(), 0);
}

TEST_F(FeatureEngineTest, AGridOverTheVoxelLimitIsNeverConverted) {
  FeatureEngine small(*store_, 100, budget_);
  Result<db::StructureRecord> s = store_->get_structure(id_);
  ASSERT_TRUE(s.ok());
  Result<std::vector<db::SeriesRecord>> series = store_->list_series("S1");
  ASSERT_TRUE(series.ok());
  const ImageGeometry image_grid = series->at(0).geometry;  // 1120 voxels
  EXPECT_EQ(small.admit(*s, image_grid, {}).status().code(), StatusCode::kResourceExhausted);
}

// convert() takes an admission (a conversion outside the budget does not compile), and only the
// one made for its structure and grid.
TEST_F(FeatureEngineTest, AConversionRunsOnlyUnderItsOwnAdmission) {
  Result<db::StructureRecord> s = store_->get_structure(id_);
  ASSERT_TRUE(s.ok());
  Result<std::vector<db::SeriesRecord>> series = store_->list_series("S1");
  ASSERT_TRUE(series.ok());
  const ImageGeometry grid = series->at(0).geometry;
  ImageGeometry other = grid;
  other.spacing_mm[0] *= 2;
  Result<FeatureEngine::Admission> admitted = features_.admit(*s, grid, {});
  ASSERT_TRUE(admitted.ok()) << admitted.status().to_string();
  EXPECT_GT(admitted->bytes(), 0);
  EXPECT_EQ(budget_.in_use(), admitted->bytes());
  EXPECT_EQ(features_.convert(*admitted, *s, other, FillRule::kNonZero).status().code(), StatusCode::kInternal);
  db::StructureRecord another = *s;
  another.id += 1;
  EXPECT_EQ(features_.convert(*admitted, another, grid, FillRule::kNonZero).status().code(), StatusCode::kInternal);
  Result<Voxelization> v = features_.convert(*admitted, *s, grid, FillRule::kNonZero);
  ASSERT_TRUE(v.ok()) << v.status().to_string();
  EXPECT_GT(voxel_count(v->volume), 0);
  admitted->shrink_to(run_length_bytes(v->volume));
  EXPECT_EQ(budget_.in_use(), run_length_bytes(v->volume));
  // Moved on, the bytes go with the new admission; the old one converts nothing.
  FeatureEngine::Admission moved = std::move(*admitted);
  EXPECT_EQ(features_.convert(*admitted, *s, grid, FillRule::kNonZero).status().code(), StatusCode::kInternal);
  EXPECT_EQ(budget_.in_use(), run_length_bytes(v->volume));
  { FeatureEngine::Admission gone = std::move(moved); }
  EXPECT_EQ(budget_.in_use(), 0);
}

// Nothing but FeatureEngine::admit makes an admission: none from nothing, none copied.
static_assert(!std::is_default_constructible_v<FeatureEngine::Admission>);
static_assert(!std::is_copy_constructible_v<FeatureEngine::Admission>);
static_assert(!std::is_copy_assignable_v<FeatureEngine::Admission>);
static_assert(!std::is_constructible_v<FeatureEngine::Admission, MemoryBudget::Reservation, int64_t, ImageGeometry>);

// The surface cache keeps a mesh from its second use on (a cold query's pass over many surfaces,
// each used once, does not fill it): the first two uses decode, the third shares the second's.
TEST_F(FeatureEngineTest, AStoredSurfaceIsKeptFromItsSecondUseAndShared) {
  Result<db::StructureRecord> s = store_->get_structure(id_);
  ASSERT_TRUE(s.ok());
  Result<std::shared_ptr<const TriangleMesh>> first = features_.surface(*s);
  ASSERT_TRUE(first.ok()) << first.status().to_string();
  EXPECT_EQ((*first)->triangles.size(), size_t(s->surface.triangle_count));
  Result<std::shared_ptr<const TriangleMesh>> second = features_.surface(*s);
  ASSERT_TRUE(second.ok());
  EXPECT_NE(first->get(), second->get());
  Result<std::shared_ptr<const TriangleMesh>> third = features_.surface(*s);
  ASSERT_TRUE(third.ok());
  EXPECT_EQ(second->get(), third->get());
  EXPECT_EQ((*third)->triangles, (*first)->triangles);
}

}  // namespace
}  // namespace soiq::server
