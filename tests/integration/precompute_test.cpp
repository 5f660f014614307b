// Precompute through a real soiqd (server/app/precompute_worker.h): the queue drains in the
// background, a query then reads every value from the feature cache, a content filter with no
// structured filter keeps in stage 1 exactly the structures whose stored values satisfy it, and the
// rows equal a brute-force evaluation of the predicate over every structure, stored or not. The
// queue survives a restart. With --precompute weighted the coverage-weighted features are stored
// too, bit for bit those a query computes, and turning it on queues the stored structures again.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <set>
#include <thread>

#include "tests/integration/cohort.h"

namespace soiq::testing {
namespace {

class PrecomputeTest : public ServiceTest {
 protected:
  void SetUp() override { restart("on"); }

  void restart(const std::string& precompute) {
    start({"--precompute", precompute, "--workers", "2"});
    client_ = std::make_unique<client::Client>(connect());
  }

  // Polls `soiq info` until the queue is empty (five minutes at most: the worker runs at nice 19,
  // and the other tests of a parallel run take most of the CPU).
  v1::ServerInfo drained() {
    for (int i = 0; i < 3000; ++i) {
      Result<v1::ServerInfo> info = client_->server_info();
      EXPECT_TRUE(info.ok()) << info.status().to_string();
      if (!info.ok() || info->precompute_queued() == 0) return info.ok() ? *info : v1::ServerInfo{};
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ADD_FAILURE() << "the precompute queue did not drain in five minutes";
    return {};
  }

  // Each structure's voxel volume as ComputeFeatures gives it on the default grid.
  double volume(int64_t id) {
    v1::FeaturesRequest req;
    req.set_structure_id(id);
    req.add_features("voxel_volume_mm3");
    Result<v1::FeaturesResponse> r = client_->compute_features(req);
    EXPECT_TRUE(r.ok()) << r.status().to_string();
    return r.ok() && r->features_size() == 1 ? r->features(0).value(0) : -1;
  }

  struct Answer {
    std::set<int64_t> ids;
    v1::QuerySummary summary;
  };
  Answer query_larger_than(double threshold, bool with_mean = false, const std::string& region = "") {
    v1::QueryRequest q;
    v1::Predicate* p = q.add_where();
    p->mutable_feature()->set_name("voxel_volume_mm3");
    p->set_op(v1::GT);
    p->set_value(threshold);
    if (with_mean) {
      q.add_select()->set_name("mean");
      q.mutable_select(0)->set_image("MR");
      q.mutable_select(0)->set_region(region);
    }
    Answer a;
    client::QueryHandlers h;
    h.on_row = [&](const v1::QueryRow& r) {
      a.ids.insert(r.structure().id());
      return true;
    };
    Result<v1::QuerySummary> s = client_->query(q, h);
    EXPECT_TRUE(s.ok()) << s.status().to_string();
    if (s.ok()) a.summary = *s;
    EXPECT_EQ(a.summary.failed(), 0);
    return a;
  }

  // Each structure's volume_w_mm3 and mean_w inside the MR image, by id, from one query, and how
  // the query got them.
  struct Weighted {
    std::map<int64_t, std::vector<double>> values;
    v1::QuerySummary summary;
  };
  Weighted query_weighted() {
    v1::QueryRequest q;
    v1::Predicate* p = q.add_where();
    p->mutable_feature()->set_name("volume_w_mm3");
    p->set_op(v1::GT);
    p->set_value(0);
    q.add_select()->set_name("mean_w");
    q.mutable_select(0)->set_image("MR");
    Weighted w;
    client::QueryHandlers h;
    h.on_row = [&](const v1::QueryRow& r) {
      std::vector<double>& v = w.values[r.structure().id()];
      for (const v1::FeatureValue& f : r.values()) v.insert(v.end(), f.value().begin(), f.value().end());
      return true;
    };
    Result<v1::QuerySummary> s = client_->query(q, h);
    EXPECT_TRUE(s.ok()) << s.status().to_string();
    if (s.ok()) w.summary = *s;
    EXPECT_EQ(w.summary.failed(), 0);
    return w;
  }
};

TEST_F(PrecomputeTest, AContentFilterIsAnsweredFromStoredValuesAndEqualsTheBruteForce) {
  const Cohort first = load_cohort(*this, *client_, dir_, 5);
  ASSERT_EQ(first.structures.size(), 20u);
  const v1::ServerInfo info = drained();
  EXPECT_TRUE(info.precompute_enabled());
  EXPECT_EQ(info.precompute_failed(), 0);
  EXPECT_GT(info.cached_features(), 20 * 6);  // shape and intensity values of each structure

  std::vector<double> volumes;
  for (const CohortStructure& s : first.structures) volumes.push_back(volume(s.id));
  std::vector<double> sorted = volumes;
  std::sort(sorted.begin(), sorted.end());
  const double threshold = sorted[sorted.size() / 2];  // about half match
  std::set<int64_t> expected;
  for (size_t i = 0; i < volumes.size(); ++i)
    if (volumes[i] > threshold) expected.insert(first.structures[i].id);
  ASSERT_FALSE(expected.empty());
  ASSERT_LT(expected.size(), first.structures.size());

  // Stage 1 keeps only the matches, and stage 2 reads everything, the image's mean included, from
  // what precompute stored.
  Answer a = query_larger_than(threshold, true);
  EXPECT_EQ(a.ids, expected);
  EXPECT_EQ(a.summary.stage1_candidates(), int64_t(expected.size()));
  EXPECT_EQ(a.summary.computed(), 0);
  EXPECT_EQ(a.summary.cache_hits(), int64_t(expected.size()));
  // A shell widens the grid's margin but not its voxel centres: the stored values still hold, and
  // precompute stored the 3 mm shell's mean too; a 5 mm shell is computed.
  a = query_larger_than(threshold, true, "shell:3");
  EXPECT_EQ(a.ids, expected);
  EXPECT_EQ(a.summary.stage1_candidates(), int64_t(expected.size()));
  EXPECT_EQ(a.summary.computed(), 0);
  a = query_larger_than(threshold, true, "shell:5");
  EXPECT_EQ(a.ids, expected);
  EXPECT_EQ(a.summary.stage1_candidates(), int64_t(expected.size()));
  EXPECT_EQ(a.summary.computed(), int64_t(expected.size()));

  // Structures that arrive with precompute off are not stored: stage 1 hands them to stage 2,
  // which decides them; the rows are still the brute force's. The first five patients' surfaces
  // come again (new structures, same surfaces: stage 2 finds their values cached by surface).
  restart("off");
  const Cohort more = load_cohort(*this, *client_, dir_, 7);
  ASSERT_EQ(more.structures.size(), 28u);
  EXPECT_EQ(client_->server_info()->precompute_queued(), 28);
  a = query_larger_than(threshold);
  EXPECT_EQ(a.summary.stage1_candidates(), int64_t(expected.size()) + 28);
  EXPECT_EQ(a.summary.computed(), 8);
  std::set<int64_t> expected_all = expected;
  for (const CohortStructure& s : more.structures)
    if (volume(s.id) > threshold) expected_all.insert(s.id);
  EXPECT_EQ(a.ids, expected_all);

  // The queue is durable: with precompute on again, it drains.
  restart("on");
  EXPECT_EQ(drained().precompute_queued(), 0);
  a = query_larger_than(threshold);
  EXPECT_EQ(a.ids, expected_all);
  EXPECT_EQ(a.summary.stage1_candidates(), int64_t(expected_all.size()));
}

TEST_F(PrecomputeTest, AQueryOnAnotherGridDoesNotUseTheStoredValues) {
  const Cohort c = load_cohort(*this, *client_, dir_, 2);
  drained();
  v1::QueryRequest q;
  v1::Predicate* p = q.add_where();
  p->mutable_feature()->set_name("voxel_volume_mm3");
  p->set_op(v1::GT);
  p->set_value(1e12);  // nothing is that large
  q.mutable_grid()->set_spacing_mm(0.5);
  client::QueryHandlers h;
  h.on_row = [](const v1::QueryRow&) { return true; };
  Result<v1::QuerySummary> s = client_->query(q, h);
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  // Values stored at 1 mm say nothing about 0.5 mm: every structure reaches stage 2.
  EXPECT_EQ(s->stage1_candidates(), int64_t(c.structures.size()));
  EXPECT_EQ(s->matched(), 0);
}

TEST_F(PrecomputeTest, WeightedPrecomputeStoresWhatAQueryWouldComputeBitForBit) {
  restart("weighted");
  const Cohort c = load_cohort(*this, *client_, dir_, 2);
  EXPECT_EQ(drained().precompute_failed(), 0);
  const Weighted stored = query_weighted();
  EXPECT_EQ(stored.summary.computed(), 0);
  EXPECT_EQ(stored.summary.cache_hits(), int64_t(c.structures.size()));
  ASSERT_EQ(stored.values.size(), c.structures.size());

  // The same cohort in a store that never precomputed: the query computes every value, and they
  // are the very same doubles.
  db_path_ = dir_.file("unprecomputed.db");
  restart("off");
  const Cohort fresh = load_cohort(*this, *client_, dir_, 2);
  const Weighted computed = query_weighted();
  EXPECT_EQ(computed.summary.computed(), int64_t(c.structures.size()));
  ASSERT_EQ(fresh.structures.size(), c.structures.size());
  for (size_t i = 0; i < c.structures.size(); ++i) {
    ASSERT_EQ(stored.values.count(c.structures[i].id), 1u);
    ASSERT_EQ(computed.values.count(fresh.structures[i].id), 1u);
    const std::vector<double>& a = stored.values.at(c.structures[i].id);
    const std::vector<double>& b = computed.values.at(fresh.structures[i].id);
    ASSERT_EQ(a.size(), 2u);  // volume_w_mm3, mean_w
    ASSERT_EQ(b.size(), 2u);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), 2 * sizeof(double)), 0)
        << c.structures[i].name << ": " << a[0] << " " << a[1] << " against " << b[0] << " " << b[1];
  }
}

TEST_F(PrecomputeTest, ByDefaultPrecomputeComputesNoCoverage) {
  const Cohort c = load_cohort(*this, *client_, dir_, 2);
  drained();
  // Precompute caches every value it computes: had it converted for coverage, these were cached.
  EXPECT_EQ(query_weighted().summary.computed(), int64_t(c.structures.size()));
}

TEST_F(PrecomputeTest, TurningWeightedOnQueuesThePrecomputedAgainAndTurningItOffKeepsTheValues) {
  const Cohort c = load_cohort(*this, *client_, dir_, 2);
  drained();
  const int64_t n = int64_t(c.structures.size());
  restart("weighted");
  EXPECT_NE(server_->log().find("event=precompute_requeued structures=" + std::to_string(n)), std::string::npos)
      << server_->log();
  // Stage 1 goes on filtering on the stored values meanwhile: nothing is that large.
  EXPECT_EQ(query_larger_than(1e12).summary.stage1_candidates(), 0);
  drained();
  EXPECT_EQ(query_weighted().summary.computed(), 0);

  // Off again: nothing is queued, nothing dropped.
  restart("on");
  EXPECT_EQ(server_->log().find("precompute_requeued"), std::string::npos) << server_->log();
  EXPECT_EQ(client_->server_info()->precompute_queued(), 0);
  EXPECT_EQ(query_weighted().summary.computed(), 0);
  EXPECT_EQ(query_larger_than(1e12).summary.stage1_candidates(), 0);
}

}  // namespace
}  // namespace soiq::testing
