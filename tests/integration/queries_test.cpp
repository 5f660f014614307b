// Features and two-stage queries through a real soiqd, checked against the same computation done
// offline (core/ directly) and a brute-force evaluation of the query over the same data.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <thread>

#include "core/features/asymmetry_index.h"
#include "core/features/structure_features.h"
#include "core/geometry/primitives.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/voxelize_1d.h"
#include "tests/integration/cohort.h"

namespace soiq::testing {
namespace {

constexpr int kMargin = 6;  // voxels: wide enough for shell:3 at 1 mm, so the server keeps it

// Offline: features of an uploaded file exactly as the server computes them (1 mm, margin 6).
std::map<std::string, double> offline_features(const CohortStructure& s, const std::string& image_path,
                                               const std::vector<std::string>& names,
                                               const std::vector<std::string>& regions) {
  Result<TriangleMesh> mesh = read_mesh(s.mesh_path);
  EXPECT_TRUE(mesh.ok());
  Result<ImageGeometry> g = grid_around(*mesh, {1, 1, 1}, kMargin);
  EXPECT_TRUE(g.ok());
  Result<Voxelization> v = voxelize_1d(*mesh, *g);
  EXPECT_TRUE(v.ok());
  Result<Image> image = read_image(image_path);
  EXPECT_TRUE(image.ok());
  FeatureRequest request;
  request.names = names;
  request.regions.clear();
  for (const auto& r : regions) request.regions.push_back(*parse_region(r));
  request.images.push_back({"MR", &*image});
  Result<FeatureReport> report = structure_features({v->volume, std::make_shared<const TriangleMesh>(*mesh)}, request);
  EXPECT_TRUE(report.ok()) << report.status().to_string();
  std::map<std::string, double> out;
  for (const Feature& f : report->features) out[f.name + (f.region.empty() ? "" : "[" + f.region + "]")] = f.value[0];
  return out;
}

v1::FeatureRef ref(const std::string& name, const std::string& region = "", const std::string& image = "",
                   bool asym = false) {
  v1::FeatureRef r;
  r.set_name(name);
  r.set_region(region);
  r.set_image(image);
  r.set_asymmetry(asym);
  return r;
}

class QueryTest : public ServiceTest {
 protected:
  void SetUp() override {
    ServiceTest::SetUp();
    cohort_ = load_cohort(*this, *client_, dir_, 10);
    ASSERT_EQ(cohort_.structures.size(), 40u);
  }
  Cohort cohort_;
};

TEST_F(QueryTest, FeaturesEqualTheOfflineOnesAndComeFromTheCacheTheSecondTime) {
  const CohortStructure& s = cohort_.structures[5];
  v1::FeaturesRequest req;
  req.set_structure_id(s.id);
  req.mutable_grid()->set_spacing_mm(1);
  req.mutable_grid()->set_margin_voxels(kMargin);
  for (const char* n : {"voxel_volume_mm3", "mesh_volume_mm3", "surface_area_mm2", "sphericity",
                        "maximum_3d_diameter_mm", "major_axis_length_mm", "mean", "p90"})
    req.add_features(n);
  req.add_regions("inside");
  req.add_regions("shell:3");
  req.add_images("MR");
  Result<v1::FeaturesResponse> first = client_->compute_features(req);
  ASSERT_TRUE(first.ok()) << first.status().to_string();
  EXPECT_FALSE(first->from_cache());
  const auto expected = offline_features(s, s.image_path,
                                         {"voxel_volume_mm3", "mesh_volume_mm3", "surface_area_mm2", "sphericity",
                                          "maximum_3d_diameter_mm", "major_axis_length_mm", "mean", "p90"},
                                         {"inside", "shell:3"});
  ASSERT_EQ(first->features_size(), 6 + 2 * 2);
  for (const v1::FeatureValue& f : first->features()) {
    const std::string key = f.name() + (f.region().empty() ? "" : "[" + f.region() + "]");
    ASSERT_TRUE(expected.count(key)) << key;
    EXPECT_DOUBLE_EQ(f.value(0), expected.at(key)) << key;
  }
  Result<v1::FeaturesResponse> second = client_->compute_features(req);
  ASSERT_TRUE(second.ok());
  EXPECT_TRUE(second->from_cache());
  ASSERT_EQ(second->features_size(), first->features_size());
  for (int i = 0; i < first->features_size(); ++i)
    EXPECT_EQ(second->features(i).value(0), first->features(i).value(0));  // bitwise: stored as float64
}

// A region asked twice (under two spellings) and one series named twice are each computed and
// answered once, with the values of the plain request.
TEST_F(QueryTest, ARegionOrImageAskedTwiceIsAnsweredOnce) {
  const CohortStructure& s = cohort_.structures[7];
  v1::FeaturesRequest req;
  req.set_structure_id(s.id);
  req.mutable_grid()->set_spacing_mm(1);
  req.mutable_grid()->set_margin_voxels(kMargin);
  req.add_features("mean");
  req.add_regions("shell:3");
  req.add_images("MR");
  Result<v1::FeaturesResponse> plain = client_->compute_features(req);
  ASSERT_TRUE(plain.ok()) << plain.status().to_string();
  ASSERT_EQ(plain->features_size(), 1);
  req.add_regions("shell:3.0");
  req.add_images("MR");
  Result<v1::FeaturesResponse> twice = client_->compute_features(req);
  ASSERT_TRUE(twice.ok()) << twice.status().to_string();
  ASSERT_EQ(twice->features_size(), 1);
  EXPECT_EQ(twice->features(0).region(), "shell:3");
  EXPECT_EQ(twice->features(0).value(0), plain->features(0).value(0));
}

TEST_F(QueryTest, TheMaskSurfaceValuesOfAStoredSurfaceAreServedAlone) {
  // Asked alone, a mask_ feature still needs the stored surface beside the mask (the server may
  // otherwise leave the mesh out of the computation).
  const CohortStructure& s = cohort_.structures[2];
  v1::FeaturesRequest req;
  req.set_structure_id(s.id);
  req.mutable_grid()->set_spacing_mm(1);
  req.mutable_grid()->set_margin_voxels(kMargin);
  req.add_features("mask_sphericity");
  Result<v1::FeaturesResponse> r = client_->compute_features(req);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  ASSERT_EQ(r->features_size(), 1);
  Result<TriangleMesh> mesh = read_mesh(s.mesh_path);
  ASSERT_TRUE(mesh.ok());
  Result<ImageGeometry> g = grid_around(*mesh, {1, 1, 1}, kMargin);
  ASSERT_TRUE(g.ok());
  Result<Voxelization> v = voxelize_1d(*mesh, *g);
  ASSERT_TRUE(v.ok());
  FeatureRequest request;
  request.names = {"mask_sphericity"};
  Result<FeatureReport> offline = structure_features({v->volume, std::make_shared<const TriangleMesh>(*mesh)}, request);
  ASSERT_TRUE(offline.ok()) << offline.status().to_string();
  ASSERT_EQ(offline->features.size(), 1u);
  EXPECT_DOUBLE_EQ(r->features(0).value(0), offline->features[0].value[0]);
}

TEST_F(QueryTest, AQueryEqualsABruteForceEvaluationColdAndWarm) {
  // Women aged 40+, hippocampi, volume over 2900 mm3 and a bright shell; ordered by the mean inside.
  // On this cohort (kCohortSeed) each of the two conditions rejects a candidate the other keeps.
  v1::QueryRequest q;
  q.mutable_stage1()->set_sex("F");
  q.mutable_stage1()->set_min_age_years(40);
  q.mutable_stage1()->set_structure_name_glob("hippo*");
  auto* w1 = q.add_where();
  *w1->mutable_feature() = ref("voxel_volume_mm3");
  w1->set_op(v1::GT);
  w1->set_value(2900);
  auto* w2 = q.add_where();
  *w2->mutable_feature() = ref("mean", "shell:3", "MR");
  w2->set_op(v1::GE);
  w2->set_value(150);
  *q.add_select() = ref("sphericity");
  *q.add_select() = ref("voxel_volume_mm3", "", "", /*asym=*/true);
  *q.mutable_order_by() = ref("mean", "inside", "MR");
  q.set_descending(true);
  q.set_limit(3);
  q.mutable_grid()->set_spacing_mm(1);
  q.mutable_grid()->set_margin_voxels(kMargin);

  // Brute force over every structure, offline.
  struct Expect {
    int64_t id;
    double order, asym;
  };
  std::vector<Expect> expected;
  int64_t candidates = 0;
  std::map<std::pair<std::string, std::string>, double> volume_of;  // (patient, name+side)
  for (const CohortStructure& s : cohort_.structures) {
    const auto f = offline_features(s, s.image_path, {"voxel_volume_mm3", "mean"}, {"inside", "shell:3"});
    volume_of[{s.patient, s.name + s.laterality}] = f.at("voxel_volume_mm3");
  }
  for (const CohortStructure& s : cohort_.structures) {
    if (s.sex != "F" || s.age < 40 || s.name != "hippocampus") continue;
    ++candidates;
    const auto f = offline_features(s, s.image_path, {"voxel_volume_mm3", "mean"}, {"inside", "shell:3"});
    if (!(f.at("voxel_volume_mm3") > 2900 && f.at("mean[shell:3]") >= 150)) continue;
    const double l = volume_of[{s.patient, s.name + "L"}], r = volume_of[{s.patient, s.name + "R"}];
    expected.push_back({s.id, f.at("mean[inside]"), *asymmetry_index(l, r)});
  }
  std::sort(expected.begin(), expected.end(), [](const Expect& a, const Expect& b) { return a.order > b.order; });
  ASSERT_GE(expected.size(), 4u) << "the cohort should give more matches than the limit";
  ASSERT_LT(expected.size(), size_t(candidates)) << "the conditions should reject some candidates";
  expected.resize(3);

  for (const bool warm : {false, true}) {
    SCOPED_TRACE(warm ? "warm" : "cold");
    std::vector<v1::QueryRow> rows;
    int64_t progress_events = 0;
    client::QueryHandlers h;
    h.on_row = [&](const v1::QueryRow& r) {
      rows.push_back(r);
      return true;
    };
    h.on_progress = [&](const v1::QueryProgress&) {
      ++progress_events;
      return true;
    };
    Result<v1::QuerySummary> summary = client_->query(q, h);
    ASSERT_TRUE(summary.ok()) << summary.status().to_string();
    EXPECT_GE(progress_events, 2);
    EXPECT_EQ(summary->failed(), 0) << (summary->failures_size() ? summary->failures(0) : "");
    EXPECT_EQ(summary->stage1_candidates(), candidates);
    EXPECT_EQ(summary->returned(), 3);
    if (warm) {
      EXPECT_EQ(summary->computed(), 0);
    } else {
      EXPECT_GT(summary->computed(), 0);
    }
    ASSERT_EQ(rows.size(), 3u);
    for (size_t i = 0; i < rows.size(); ++i) {
      EXPECT_EQ(rows[i].structure().id(), expected[i].id) << i;
      // values: where (2), select (2), order_by (1)
      ASSERT_EQ(rows[i].values_size(), 5);
      EXPECT_EQ(rows[i].values(3).name(), "asym(voxel_volume_mm3)");
      EXPECT_DOUBLE_EQ(rows[i].values(3).value(0), expected[i].asym);
      EXPECT_DOUBLE_EQ(rows[i].values(4).value(0), expected[i].order);
      EXPECT_EQ(rows[i].patient().sex(), "F");
    }
  }
}

// The coverage-weighted features on soiqd equal the offline ones bit for bit, come from the cache
// the second time, and a query filters and orders by them; a shell has no weights (only inside).
TEST_F(QueryTest, CoverageWeightedFeaturesAreComputedCachedAndQueried) {
  const std::vector<std::string> names = {"volume_w_mm3", "mean_w", "variance_w", "integrated_intensity_w"};
  const CohortStructure& s = cohort_.structures[7];
  v1::FeaturesRequest req;
  req.set_structure_id(s.id);
  req.mutable_grid()->set_spacing_mm(1);
  req.mutable_grid()->set_margin_voxels(kMargin);
  for (const std::string& n : names) req.add_features(n);
  req.add_regions("inside");
  req.add_images("MR");
  Result<v1::FeaturesResponse> first = client_->compute_features(req);
  ASSERT_TRUE(first.ok()) << first.status().to_string();
  const auto expected = offline_features(s, s.image_path, names, {"inside"});
  ASSERT_EQ(first->features_size(), 4);
  for (const v1::FeatureValue& f : first->features()) {
    const std::string key = f.name() + (f.region().empty() ? "" : "[" + f.region() + "]");
    ASSERT_TRUE(expected.count(key)) << key;
    EXPECT_DOUBLE_EQ(f.value(0), expected.at(key)) << key;
  }
  Result<v1::FeaturesResponse> second = client_->compute_features(req);
  ASSERT_TRUE(second.ok());
  EXPECT_TRUE(second->from_cache());

  // Hippocampi whose weighted mean inside exceeds the median of all of them, ordered by it.
  std::vector<std::pair<double, int64_t>> means;
  for (const CohortStructure& c : cohort_.structures) {
    if (c.name != "hippocampus") continue;
    means.push_back({offline_features(c, c.image_path, {"mean_w"}, {"inside"}).at("mean_w[inside]"), c.id});
  }
  std::sort(means.rbegin(), means.rend());
  const double cut = means[means.size() / 2].first;
  v1::QueryRequest q;
  q.mutable_stage1()->set_structure_name_glob("hippo*");
  auto* w = q.add_where();
  *w->mutable_feature() = ref("mean_w", "inside", "MR");
  w->set_op(v1::GT);
  w->set_value(cut);
  *q.mutable_order_by() = ref("mean_w", "inside", "MR");
  q.set_descending(true);
  q.mutable_grid()->set_spacing_mm(1);
  q.mutable_grid()->set_margin_voxels(kMargin);
  std::vector<v1::QueryRow> rows;
  client::QueryHandlers h;
  h.on_row = [&](const v1::QueryRow& r) {
    rows.push_back(r);
    return true;
  };
  Result<v1::QuerySummary> summary = client_->query(q, h);
  ASSERT_TRUE(summary.ok()) << summary.status().to_string();
  EXPECT_EQ(summary->failed(), 0) << (summary->failures_size() ? summary->failures(0) : "");
  ASSERT_EQ(rows.size(), means.size() / 2);
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].structure().id(), means[i].second) << i;
    EXPECT_DOUBLE_EQ(rows[i].values(0).value(0), means[i].first) << i;
  }

  // In a shell the weighted features have no meaning: refused, naming the region.
  v1::QueryRequest shell = q;
  *shell.mutable_where(0)->mutable_feature() = ref("mean_w", "shell:3", "MR");
  Result<v1::QuerySummary> refused = client_->query(shell, {});
  EXPECT_EQ(refused.status().code(), StatusCode::kInvalidArgument) << refused.status().to_string();
  EXPECT_NE(refused.status().message().find("inside"), std::string::npos) << refused.status().message();
}

TEST_F(QueryTest, RowsStreamWithoutOrderAndALimitStopsEarly) {
  v1::QueryRequest q;
  q.mutable_stage1()->set_laterality("L");
  auto* w = q.add_where();
  *w->mutable_feature() = ref("voxel_volume_mm3");
  w->set_op(v1::GT);
  w->set_value(0);
  q.set_limit(5);
  std::vector<int64_t> ids;
  client::QueryHandlers h;
  h.on_row = [&](const v1::QueryRow& r) {
    ids.push_back(r.structure().id());
    EXPECT_EQ(r.structure().laterality(), "L");
    return true;
  };
  Result<v1::QuerySummary> s = client_->query(q, h);
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  EXPECT_EQ(s->stage1_candidates(), 20);
  EXPECT_EQ(ids.size(), 5u);
  EXPECT_EQ(s->returned(), 5);
}

TEST_F(QueryTest, AStructureWithoutTheImageFailsAloneAndIsReported) {
  // A patient with no image: its structure cannot have an intensity feature; the others still can.
  ASSERT_TRUE(upload(uv_sphere({0, 0, 0}, 5, 12, 24), "NOIMG", "9.9", "hippocampus", "L").ok());
  v1::QueryRequest q;
  q.mutable_stage1()->set_structure_name_glob("hippocampus");
  q.mutable_stage1()->set_laterality("L");
  *q.add_select() = ref("mean", "inside", "MR");
  Result<v1::QuerySummary> s = client_->query(q, {});
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  EXPECT_EQ(s->stage1_candidates(), 11);
  EXPECT_EQ(s->failed(), 1);
  EXPECT_EQ(s->returned(), 10);
  ASSERT_EQ(s->failures_size(), 1);
  EXPECT_NE(s->failures(0).find("no image series 'MR'"), std::string::npos) << s->failures(0);
}

TEST_F(QueryTest, MalformedQueriesAreInvalidArguments) {
  auto expect_invalid = [&](const v1::QueryRequest& q, const std::string& words) {
    Result<v1::QuerySummary> s = client_->query(q, {});
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.status().code(), StatusCode::kInvalidArgument) << s.status().to_string();
    EXPECT_NE(s.status().message().find(words), std::string::npos) << s.status().message();
  };
  v1::QueryRequest unknown;
  *unknown.add_select() = ref("roundness");
  expect_invalid(unknown, "roundness");
  v1::QueryRequest no_image;
  *no_image.add_select() = ref("mean", "inside", "");
  expect_invalid(no_image, "needs an image");
  v1::QueryRequest bad_region;
  *bad_region.add_select() = ref("mean", "shell:-1", "MR");
  expect_invalid(bad_region, "shell");
  v1::QueryRequest bad_date;
  bad_date.mutable_stage1()->set_study_date_from("2024-01-01");
  expect_invalid(bad_date, "YYYYMMDD");
  v1::QueryRequest array_predicate;
  auto* w = array_predicate.add_where();
  *w->mutable_feature() = ref("centroid_mm");
  w->set_op(v1::GT);
  expect_invalid(array_predicate, "array");
}

TEST_F(QueryTest, ADeadlineStopsAQueryMidwayAndTheServerCarriesOn) {
  // A fine grid makes every structure slow: at 0.1 mm each has tens of millions of grid voxels, so
  // 40 of them take seconds (at 0.25 mm a fast machine finished all 40 inside the deadline).
  v1::QueryRequest q;
  *q.add_select() = ref("mean", "shell:3", "MR");
  q.mutable_grid()->set_spacing_mm(0.1);
  client::ClientOptions o;
  o.address = server_->address();
  o.stream_deadline = std::chrono::milliseconds(300);
  o.retry.attempts = 1;
  Result<client::Client> hasty = client::Client::connect(o);
  ASSERT_TRUE(hasty.ok());
  Result<v1::QuerySummary> s = hasty->query(q, {});
  ASSERT_FALSE(s.ok()) << s->DebugString();
  EXPECT_EQ(s.status().code(), StatusCode::kDeadlineExceeded) << s.status().to_string();
  // The server is still there and answers.
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->structures(), 40);
}

}  // namespace
}  // namespace soiq::testing
