// The query engine on its own, without gRPC: a real SQLite store of boxes whose volumes are known
// exactly (mesh_volume_mm3 of a box is the product of its sides), queried through every step:
// stage 1 with twins, the cache, computation on the pool, predicates, order and limit, failures
// and stops.
#include "server/app/query_engine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/geometry/primitives.h"
#include "tests/db/temp_store.h"
#include "tests/server/stored_box.h"

namespace soiq::server {
namespace {

using db::testing::TempDir;

class QueryEngineTest : public ::testing::Test {
 protected:
  // A box of `x` x 10 x 10 mm in study S1 of patient P1: mesh_volume_mm3 = 100 x.
  int64_t add_box(const std::string& name, const std::string& laterality, double x, const std::string& study = "S1") {
    // Distinct positions give distinct surfaces (and cache keys) for equal sizes.
    const double at = double(++boxes_) * 100;
    return testing::add_stored_box(*store_, {at, 0, 0}, {at + x, 10, 10}, name, study, laterality);
  }

  static QueryFeature shape(const std::string& name, bool asymmetry = false) {
    QueryFeature f;
    f.name = name;
    f.asymmetry = asymmetry;
    f.label.name = asymmetry ? "asym(" + name + ")" : name;
    return f;
  }

  // A PT series of patient P1 in `study`.
  void add_pt_series(const std::string& study) {
    db::NewSeries s = db::testing::new_series("P1", study, study + ".9", 1.0f);
    s.series.modality = "PT";
    const Result<bool> put = store_->put_series(s);
    ASSERT_TRUE(put.ok()) << put.status().to_string();
  }

  static QueryFeature mean_of(const std::string& image) {
    QueryFeature f;
    f.name = "mean";
    f.intensity = true;
    f.image = image;
    f.label = {"mean", "inside", image};
    return f;
  }

  // A query over every structure reading `features`, with the ask that covers them.
  static Query query_of(std::vector<QueryFeature> features) {
    Query q;
    q.limit = 100;
    for (const QueryFeature& f : features) {
      q.ask.names.push_back(f.name);
      q.stage1.twins = q.stage1.twins || f.asymmetry;
      if (!f.intensity) continue;
      q.ask.regions.push_back(f.region);
      q.ask.images.push_back(f.image);
    }
    q.features = std::move(features);
    const Status complete = complete_feature_ask(q.ask);
    EXPECT_TRUE(complete.ok()) << complete.to_string();
    return q;
  }

  struct Ran {
    Result<QuerySummary> summary;
    std::vector<QueryRow> rows;
    std::vector<QueryProgress> progress;
  };

  Ran run(
      const Query& q, std::function<Status()> stop = [] { return ok_status(); }) {
    Ran ran{Status(StatusCode::kInternal, "not run"), {}, {}};
    const QueryOutput out{[&](const QueryProgress& p) {
                            ran.progress.push_back(p);
                            return ok_status();
                          },
                          [&](QueryRow&& r) {
                            ran.rows.push_back(std::move(r));
                            return ok_status();
                          }};
    ran.summary = engine_.run(q, stop, out);
    return ran;
  }

  TempDir tmp_;
  std::unique_ptr<db::SqliteStore> store_ = db::testing::open_store(tmp_.file("soiq.db"));
  MemoryBudget budget_{int64_t(1) << 30};
  FeatureEngine features_{*store_, int64_t(1) << 26, budget_};
  WorkerPool pool_{2};
  QueryEngine engine_{*store_, features_, pool_, QueryLimits{}};
  int boxes_ = 0;
};

TEST_F(QueryEngineTest, EveryMatchComesWithItsValuesRecordsAndASummary) {
  const int64_t a = add_box("a", "", 10);
  const int64_t b = add_box("b", "", 20);
  Query q = query_of({shape("mesh_volume_mm3")});
  q.where.push_back({0, Comparison::kGreater, 1500});
  Ran ran = run(q);
  ASSERT_TRUE(ran.summary.ok()) << ran.summary.status().to_string();
  ASSERT_EQ(ran.rows.size(), 1u);
  EXPECT_EQ(ran.rows[0].structure.id, b);
  EXPECT_EQ(ran.rows[0].patient.patient_id, "P1");
  EXPECT_EQ(ran.rows[0].study.study_uid, "S1");
  ASSERT_EQ(ran.rows[0].values.size(), 1u);
  EXPECT_EQ(ran.rows[0].values[0].label.name, "mesh_volume_mm3");
  ASSERT_EQ(ran.rows[0].values[0].values.size(), 1u);
  EXPECT_NEAR(ran.rows[0].values[0].values[0], 2000, 1e-9);  // exact up to rounding of the sum
  EXPECT_EQ(ran.summary->stage1_candidates, 2);
  EXPECT_EQ(ran.summary->computed, 2);
  EXPECT_EQ(ran.summary->matched, 1);
  EXPECT_EQ(ran.summary->returned, 1);
  EXPECT_EQ(ran.summary->failed, 0);
  ASSERT_FALSE(ran.progress.empty());
  EXPECT_EQ(ran.progress.front().stage, "stage1");
  EXPECT_EQ(ran.progress.back().stage, "stage2");
  EXPECT_EQ(ran.progress.back().done, 2);
  EXPECT_EQ(ran.progress.back().total, 2);
  (void)a;
}

TEST_F(QueryEngineTest, ASecondRunIsAnsweredFromTheCacheWithTheSameValues) {
  add_box("a", "", 10);
  add_box("b", "", 30);
  const Query q = query_of({shape("mesh_volume_mm3"), shape("voxel_count")});
  Ran first = run(q);
  Ran second = run(q);
  ASSERT_TRUE(first.summary.ok() && second.summary.ok());
  EXPECT_EQ(first.summary->computed, 2);
  EXPECT_EQ(first.summary->cache_hits, 0);
  EXPECT_EQ(second.summary->computed, 0);
  EXPECT_EQ(second.summary->cache_hits, 2);
  ASSERT_EQ(first.rows.size(), 2u);
  ASSERT_EQ(second.rows.size(), 2u);
  // Without an order, rows stream as the workers finish: compare them structure by structure.
  const auto by_id = [](const QueryRow& a, const QueryRow& b) { return a.structure.id < b.structure.id; };
  std::sort(first.rows.begin(), first.rows.end(), by_id);
  std::sort(second.rows.begin(), second.rows.end(), by_id);
  for (size_t r = 0; r < 2; ++r) {
    ASSERT_EQ(first.rows[r].structure.id, second.rows[r].structure.id);
    for (size_t v = 0; v < 2; ++v) EXPECT_EQ(first.rows[r].values[v].values, second.rows[r].values[v].values);
  }
}

TEST_F(QueryEngineTest, AnOrderSortsEveryMatchThenKeepsTheFirstLimit) {
  for (double x : {30.0, 10.0, 50.0, 20.0, 40.0}) add_box("s", "", x);
  Query q = query_of({shape("mesh_volume_mm3")});
  q.order_by = 0;
  q.descending = true;
  q.limit = 2;
  Ran ran = run(q);
  ASSERT_TRUE(ran.summary.ok());
  ASSERT_EQ(ran.rows.size(), 2u);
  EXPECT_NEAR(ran.rows[0].values[0].values[0], 5000, 1e-9);
  EXPECT_NEAR(ran.rows[1].values[0].values[0], 4000, 1e-9);
  EXPECT_EQ(ran.summary->matched, 5);
  EXPECT_EQ(ran.summary->returned, 2);
}

TEST_F(QueryEngineTest, AnAsymmetryReadsTheTwinEvenWhenStage1DoesNotKeepIt) {
  const int64_t left = add_box("Hippocampus", "L", 10);
  add_box("hippocampus", "R", 8);        // the twin: same name but for case, other side
  add_box("hippocampus", "R", 2, "S2");  // another study: never the twin
  Query q = query_of({shape("mesh_volume_mm3", true)});
  q.stage1.laterality = "L";
  Ran ran = run(q);
  ASSERT_TRUE(ran.summary.ok()) << ran.summary.status().to_string();
  ASSERT_EQ(ran.rows.size(), 1u);
  EXPECT_EQ(ran.rows[0].structure.id, left);
  EXPECT_EQ(ran.rows[0].values[0].label.name, "asym(mesh_volume_mm3)");
  ASSERT_EQ(ran.rows[0].values[0].values.size(), 1u);
  EXPECT_NEAR(ran.rows[0].values[0].values[0], (1000.0 - 800.0) / 900.0, 1e-12);
  EXPECT_EQ(ran.summary->computed, 2);  // the structure and its twin
}

TEST_F(QueryEngineTest, AStructureWithoutTwinHasNoAsymmetryAndMatchesNoPredicateOnIt) {
  add_box("amygdala", "L", 10);
  add_box("insula", "", 10);
  Query q = query_of({shape("mesh_volume_mm3", true)});
  Ran selected = run(q);
  ASSERT_TRUE(selected.summary.ok());
  ASSERT_EQ(selected.rows.size(), 2u);
  for (const QueryRow& row : selected.rows) EXPECT_TRUE(row.values[0].values.empty()) << row.structure.name;
  q.where.push_back({0, Comparison::kNotEqual, 12345});
  Ran filtered = run(q);
  ASSERT_TRUE(filtered.summary.ok());
  EXPECT_TRUE(filtered.rows.empty());
}

TEST_F(QueryEngineTest, AStructureWhoseFeaturesCannotBeHadIsCountedAsFailedWithItsReason) {
  const int64_t id = add_box("a", "", 10);
  add_pt_series("S2");  // the store holds PT, but not in study S1
  Ran ran = run(query_of({mean_of("PT")}));
  ASSERT_TRUE(ran.summary.ok()) << ran.summary.status().to_string();
  EXPECT_TRUE(ran.rows.empty());
  EXPECT_EQ(ran.summary->failed, 1);
  ASSERT_EQ(ran.summary->failures.size(), 1u);
  EXPECT_NE(ran.summary->failures[0].find("structure " + std::to_string(id) + ": NOT_FOUND"), std::string::npos)
      << ran.summary->failures[0];
}

// Two names of one series (its modality and its uid) are one image to compute on: each feature
// still finds its value.
TEST_F(QueryEngineTest, AnImageNamedByModalityAndByUidGivesBothFeaturesTheSameValue) {
  // A box over the series' voxel centres (temp_store.h's new_series), in a study whose series uid
  // reads as a uid.
  add_pt_series("1.2.3");
  testing::add_stored_box(*store_, {-10.4, 19.5, 29}, {-8.6, 21.9, 33.5}, "small", "1.2.3", "");
  Ran ran = run(query_of({mean_of("PT"), mean_of("1.2.3.9")}));
  ASSERT_TRUE(ran.summary.ok()) << ran.summary.status().to_string();
  EXPECT_EQ(ran.summary->failed, 0) << (ran.summary->failures.empty() ? "" : ran.summary->failures[0]);
  ASSERT_EQ(ran.rows.size(), 1u);
  ASSERT_EQ(ran.rows[0].values.size(), 2u);
  ASSERT_EQ(ran.rows[0].values[0].values.size(), 1u);
  EXPECT_EQ(ran.rows[0].values[0].values, ran.rows[0].values[1].values);
}

TEST_F(QueryEngineTest, SkippedStructuresAreCountedByReasonLargestFirstWithTheirIds) {
  add_pt_series("S2");  // the store holds PT, but not in S1 or S3
  std::vector<int64_t> s1, s3;
  for (int i = 0; i < 7; ++i) s1.push_back(add_box("in_s1", "", 10, "S1"));
  for (int i = 0; i < 2; ++i) s3.push_back(add_box("in_s3", "", 10, "S3"));
  Ran ran = run(query_of({mean_of("PT")}));
  ASSERT_TRUE(ran.summary.ok()) << ran.summary.status().to_string();
  EXPECT_TRUE(ran.rows.empty());
  EXPECT_EQ(ran.summary->failed, 9);
  ASSERT_EQ(ran.summary->skipped.size(), 1u);  // one reason, whatever the study: "their study"
  const QuerySkip& k = ran.summary->skipped[0];
  EXPECT_EQ(k.count, 9);
  EXPECT_EQ(k.reason, "NOT_FOUND: no image series 'PT' in their study (by uid or modality; upload one)");
  EXPECT_EQ(k.structure_ids, std::vector<int64_t>(s1.begin(), s1.begin() + 5));
}

TEST_F(QueryEngineTest, AnImageNoStoredSeriesHasIsRefusedBeforeStage1NamingWhatTheStoreHolds) {
  add_box("a", "", 10);
  add_pt_series("S2");
  Ran ran = run(query_of({mean_of("MR")}));
  ASSERT_FALSE(ran.summary.ok());
  EXPECT_EQ(ran.summary.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(ran.summary.status().message(), "no image in this soiqd has modality 'MR'; it holds PT");
  EXPECT_TRUE(ran.progress.empty());  // refused before stage 1 said anything
  Ran uid = run(query_of({mean_of("1.2.999")}));
  ASSERT_FALSE(uid.summary.ok());
  EXPECT_EQ(uid.summary.status().code(), StatusCode::kNotFound);
  EXPECT_NE(uid.summary.status().message().find("no image series '1.2.999'"), std::string::npos)
      << uid.summary.status().message();
  Ran grid = run([&] {
    Query q = query_of({shape("voxel_count")});
    q.ask.grid.kind = GridChoice::Kind::kSeriesModality;
    q.ask.grid.series = "CT";
    return q;
  }());
  EXPECT_EQ(grid.summary.status().code(), StatusCode::kNotFound);
  EXPECT_NE(grid.summary.status().message().find("modality 'CT'"), std::string::npos);
}

TEST_F(QueryEngineTest, AModalityUploadedAfterARefusalIsAcceptedByTheNextQuery) {
  add_box("a", "", 10);
  add_pt_series("S2");
  ASSERT_TRUE(run(query_of({mean_of("PT")})).summary.ok());  // PT now known to the engine
  EXPECT_EQ(run(query_of({mean_of("MR")})).summary.status().code(), StatusCode::kNotFound);
  db::NewSeries mr = db::testing::new_series("P1", "S3", "S3.1", 1.0f);  // new_series makes MR
  ASSERT_TRUE(store_->put_series(mr).ok());
  Ran ran = run(query_of({mean_of("MR")}));
  ASSERT_TRUE(ran.summary.ok()) << ran.summary.status().to_string();
  EXPECT_EQ(ran.summary->failed, 1);  // the box's study S1 has no MR: skipped, said so
}

TEST_F(QueryEngineTest, AStopEndsTheRunWithItsStatus) {
  add_box("a", "", 10);
  add_box("b", "", 20);
  Ran ran = run(query_of({shape("voxel_count")}),
                [] { return Status(StatusCode::kDeadlineExceeded, "the request ran past its deadline"); });
  EXPECT_EQ(ran.summary.status().code(), StatusCode::kDeadlineExceeded);
}

TEST_F(QueryEngineTest, AClosedOutputEndsTheRunWithItsStatus) {
  add_box("a", "", 10);
  const QueryOutput out{[](const QueryProgress&) { return ok_status(); },
                        [](QueryRow&&) { return Status(StatusCode::kCancelled, "the client closed the stream"); }};
  Result<QuerySummary> r = engine_.run(
      query_of({shape("voxel_count")}), [] { return ok_status(); }, out);
  EXPECT_EQ(r.status().code(), StatusCode::kCancelled);
  EXPECT_NE(r.status().message().find("closed the stream"), std::string::npos);
}

TEST_F(QueryEngineTest, MoreCandidatesThanTheStage1CapIsResourceExhaustedBeforeAnyComputation) {
  for (int i = 0; i < 3; ++i) add_box("s", "", 10);
  QueryEngine capped(*store_, features_, pool_, QueryLimits{100, 2});
  const QueryOutput out{[](const QueryProgress&) { return ok_status(); }, [](QueryRow&&) { return ok_status(); }};
  Result<QuerySummary> r = capped.run(
      query_of({shape("voxel_count")}), [] { return ok_status(); }, out);
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted);
  EXPECT_NE(r.status().message().find("narrow the stage-1 filter"), std::string::npos);
  Result<db::Counts> counts = store_->counts();
  ASSERT_TRUE(counts.ok());
  EXPECT_EQ(counts->cached_features, 0);
}

TEST(Compare, NaNNeverMatchesAndEachOperatorComparesAsItsName) {
  EXPECT_TRUE(compare(1, Comparison::kLess, 2));
  EXPECT_FALSE(compare(2, Comparison::kLess, 2));
  EXPECT_TRUE(compare(2, Comparison::kLessOrEqual, 2));
  EXPECT_TRUE(compare(3, Comparison::kGreater, 2));
  EXPECT_TRUE(compare(2, Comparison::kGreaterOrEqual, 2));
  EXPECT_TRUE(compare(2, Comparison::kEqual, 2));
  EXPECT_TRUE(compare(1, Comparison::kNotEqual, 2));
  for (Comparison op : {Comparison::kLess, Comparison::kLessOrEqual, Comparison::kGreater, Comparison::kGreaterOrEqual,
                        Comparison::kEqual, Comparison::kNotEqual})
    EXPECT_FALSE(compare(std::nan(""), op, 0));
}

}  // namespace
}  // namespace soiq::server
