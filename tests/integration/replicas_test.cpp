// Three soiqd replicas on one PostgreSQL database share a query's stage 2 (docs/SCALE_OUT.md): the
// query's rows equal a single soiqd's on the same cohort, even when one replica is killed while it
// holds part of the work; the others take its share once it is silent.
#include <gtest/gtest.h>
#include <libpq-fe.h>

#include <cstdlib>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "tests/integration/cohort.h"
#include "tests/support/postgres_process.h"

namespace soiq::testing {
namespace {

constexpr int kPatients = 10;  // 40 structures

// A query with real work per structure: a fine grid and intensities inside and in a shell.
v1::QueryRequest heavy_query() {
  v1::QueryRequest q;
  q.mutable_grid()->set_spacing_mm(0.25);
  q.mutable_grid()->set_margin_voxels(14);
  for (const auto& [name, region] : std::vector<std::pair<std::string, std::string>>{
           {"voxel_volume_mm3", ""}, {"sphericity", ""}, {"mean", "inside"}, {"mean", "shell:3"}}) {
    v1::FeatureRef* f = q.add_select();
    f->set_name(name);
    f->set_region(region);
    if (!region.empty()) f->set_image("MR");
  }
  return q;
}

using RowKey = std::tuple<std::string, std::string, std::string, std::string>;  // patient, study, name, side

std::map<RowKey, std::vector<double>> rows_of(const client::Client& c, const v1::QueryRequest& q,
                                              const std::function<void(const v1::QueryProgress&)>& on_progress,
                                              v1::QuerySummary* summary) {
  std::map<RowKey, std::vector<double>> rows;
  client::QueryHandlers h;
  h.on_row = [&](const v1::QueryRow& r) {
    std::vector<double>& values =
        rows[{r.structure().patient_id(), r.structure().study_uid(), r.structure().name(), r.structure().laterality()}];
    for (const v1::FeatureValue& v : r.values()) values.insert(values.end(), v.value().begin(), v.value().end());
    return true;
  };
  h.on_progress = [&](const v1::QueryProgress& p) {
    if (on_progress) on_progress(p);
    return true;
  };
  Result<v1::QuerySummary> s = c.query(q, h);
  EXPECT_TRUE(s.ok()) << s.status().to_string();
  if (s.ok() && summary) *summary = *s;
  return rows;
}

class ReplicasTest : public ServiceTest {
 protected:
  void SetUp() override {
    // PostgreSQL either way: the test starts its replicas on it itself, once.
    if (soiqd_on_postgres()) GTEST_SKIP() << "runs in the plain pass only; it starts its own PostgreSQL replicas";
    std::string why;
    PostgresProcess& server = shared_postgres(why);
    ASSERT_EQ(why, "");
    const std::string database = unique_postgres_database_name("replicas");
    ASSERT_EQ(ensure_postgres_database(server, database), "");
    uri_ = "postgresql://" + std::string(PostgresProcess::kUser) + "@127.0.0.1:" + std::to_string(server.port()) + "/" +
           database + "?connect_timeout=5";
  }
  // `timeout_ms`: short where a test waits for a death, longer where a busy machine must not make a
  // live replica look dead.
  std::unique_ptr<SoiqdProcess> replica(const std::string& id, const std::string& precompute = "off",
                                        int timeout_ms = 1000) {
    auto p = std::make_unique<SoiqdProcess>(
        dir_.file(id + ".db"),  // the folder of its log; the store is --db
        std::vector<std::string>{"--db", uri_, "--replica-id", id, "--replica-timeout-ms", std::to_string(timeout_ms),
                                 "--workers", "1", "--precompute", precompute});
    EXPECT_FALSE(p->address().empty()) << "replica " << id << " did not start:\n" << p->log();
    return p;
  }
  client::Client client_of(const SoiqdProcess& p) {
    client::ClientOptions o;
    o.address = p.address();
    o.retry.attempts = 1;
    Result<client::Client> c = client::Client::connect(o);
    EXPECT_TRUE(c.ok()) << c.status().to_string();
    return std::move(c).value();
  }

  // The stage-2 items `replica` holds now, read from the database as another client would.
  int64_t claims_of(const std::string& replica) {
    PGconn* c = PQconnectdb((uri_.substr(0, uri_.find('?'))).c_str());
    int64_t n = -1;
    if (PQstatus(c) == CONNECTION_OK) {
      const char* params[] = {replica.c_str()};
      PGresult* r = PQexecParams(c, "SELECT count(*) FROM stage2_work WHERE claimed_by = $1", 1, nullptr, params,
                                 nullptr, nullptr, 0);
      if (PQresultStatus(r) == PGRES_TUPLES_OK) n = std::atoll(PQgetvalue(r, 0, 0));
      PQclear(r);
    }
    PQfinish(c);
    return n;
  }

  std::string uri_;
};

TEST_F(ReplicasTest, AQuerySharedByThreeReplicasOneKilledMidwayEqualsOneSoiqdAlone) {
  // One soiqd alone, on a SQLite file, with the same cohort: the reference rows.
  std::map<RowKey, std::vector<double>> alone;
  {
    SoiqdProcess single(dir_.file("alone.db"));
    ASSERT_FALSE(single.address().empty()) << single.log();
    client::Client c = client_of(single);
    ASSERT_EQ(load_cohort(*this, c, dir_, kPatients).structures.size(), size_t(4 * kPatients));
    alone = rows_of(c, heavy_query(), {}, nullptr);
  }
  ASSERT_EQ(alone.size(), size_t(4 * kPatients));

  std::unique_ptr<SoiqdProcess> a = replica("A"), b = replica("B"), c = replica("C");
  ASSERT_TRUE(a->running() && b->running() && c->running());
  client::Client to_a = client_of(*a);
  ASSERT_EQ(load_cohort(*this, to_a, dir_, kPatients).structures.size(), size_t(4 * kPatients));
  std::this_thread::sleep_for(std::chrono::milliseconds(700));  // every replica has heard the others

  bool killed = false;
  int64_t done_at_kill = -1, b_held = 0;
  v1::QuerySummary summary;
  const std::map<RowKey, std::vector<double>> shared = rows_of(
      to_a, heavy_query(),
      [&](const v1::QueryProgress& p) {
        if (killed || p.stage() != "stage2") return;
        b_held = claims_of("B");
        if (b_held < 1) return;  // the next report, then
        b->kill_hard();          // mid-query: B holds claims it will never finish
        killed = true;
        done_at_kill = p.done();
      },
      &summary);
  ASSERT_TRUE(killed) << "B never held a claim while the query reported progress";
  EXPECT_GE(b_held, 1);
  EXPECT_LT(done_at_kill, 4 * kPatients) << "B was killed after the work was done";
  EXPECT_EQ(summary.failed(), 0);
  EXPECT_EQ(summary.computed(), 4 * kPatients);
  ASSERT_EQ(shared.size(), alone.size());
  for (const auto& [key, values] : alone) {
    auto it = shared.find(key);
    ASSERT_NE(it, shared.end()) << std::get<0>(key) << " " << std::get<2>(key) << std::get<3>(key);
    EXPECT_EQ(it->second, values) << std::get<0>(key) << " " << std::get<2>(key) << std::get<3>(key);
  }
  // C took part: its share is in its log when it stops.
  ASSERT_EQ(c->terminate(), 0);
  EXPECT_NE(c->log().find("event=replica_stopped"), std::string::npos) << c->log();
  EXPECT_EQ(c->log().find("items_computed=0"), std::string::npos) << "C computed nothing:\n" << c->log();
}

TEST_F(ReplicasTest, OneReplicaPrecomputesForAll) {
  std::unique_ptr<SoiqdProcess> a = replica("A", "on", 5000), b = replica("B", "on", 5000),
                                c = replica("C", "on", 5000);
  ASSERT_TRUE(a->running() && b->running() && c->running());
  std::this_thread::sleep_for(std::chrono::milliseconds(2000));  // every replica has heard the others
  client::Client to_c = client_of(*c);
  ASSERT_EQ(load_cohort(*this, to_c, dir_, 3).structures.size(), 12u);
  for (int i = 0; i < 600; ++i) {  // at most a minute
    Result<v1::ServerInfo> info = to_c.server_info();
    ASSERT_TRUE(info.ok()) << info.status().to_string();
    if (info->precompute_queued() == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  int64_t total = 0;
  int precomputing = 0;
  for (auto* r : {a.get(), b.get(), c.get()}) {
    ASSERT_EQ(r->terminate(), 0);
    const std::string log = r->log();
    const size_t at = log.rfind("structures_precomputed=");
    ASSERT_NE(at, std::string::npos) << log;
    const int64_t n = std::atoll(log.c_str() + at + 23);
    total += n;
    precomputing += n > 0;
  }
  EXPECT_EQ(total, 12);        // each structure once
  EXPECT_EQ(precomputing, 1);  // by A, the first id: not the replica the uploads went to
}

}  // namespace
}  // namespace soiq::testing
