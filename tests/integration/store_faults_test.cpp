// The store fails under soiqd, as it does in production: PostgreSQL goes down and comes back while
// replicas take uploads and queries, and a SQLite store's disk fills up. soiqd answers each call
// with a status that says what happened (UNAVAILABLE, RESOURCE_EXHAUSTED naming the store), keeps
// running, recovers on its own, and loses nothing it acknowledged. Both tests make their own store
// (a PostgreSQL of their own to stop, a small tmpfs), so they run in the plain pass only.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "core/geometry/primitives.h"
#include "tests/integration/service_fixture.h"
#include "tests/support/child_process.h"
#include "tests/support/postgres_process.h"

namespace soiq::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::steady_clock;

client::Client client_to(const SoiqdProcess& p) {
  client::ClientOptions o;
  o.address = p.address();
  o.retry.attempts = 1;  // the test sees every failure, not the client's retries
  Result<client::Client> c = client::Client::connect(o);
  EXPECT_TRUE(c.ok()) << c.status().to_string();
  return std::move(c).value();
}

// A sphere no other upload of the test has (its radius is its index), so none is deduplicated.
TriangleMesh nth_sphere(int i, int64_t triangles = 2000) {
  return uv_sphere_with_triangles({0, 0, 0}, 5.0 + 0.01 * i, triangles);
}

v1::QueryRequest volume_query() {
  v1::QueryRequest q;
  v1::FeatureRef* f = q.add_select();
  f->set_name("voxel_volume_mm3");
  return q;
}

// Every structure id the store lists, page after page.
Result<std::set<int64_t>> listed_ids(const client::Client& c) {
  std::set<int64_t> ids;
  v1::ListStructuresRequest r;
  r.set_page_size(1000);
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(v1::ListStructuresResponse page, c.list_structures(r));
    for (const v1::Structure& s : page.structures()) ids.insert(s.id());
    if (page.next_page_token().empty()) return ids;
    r.set_page_token(page.next_page_token());
  }
}

class StoreFaultsTest : public ServiceTest {
 protected:
  void SetUp() override {
    if (soiqd_on_postgres()) GTEST_SKIP() << "runs in the plain pass only; it makes its own store to break";
  }

  // Uploads through `c` as `patient`; the structure's id when acknowledged, else the status.
  Result<int64_t> upload_to(const client::Client& c, int i, const std::string& patient) {
    Result<v1::UploadSurfaceResponse> r =
        c.upload_surface(surface_header(patient, "1.2.3." + std::to_string(i), "ball" + std::to_string(i), ""),
                         write_mesh_file(nth_sphere(i), "stl"));
    if (!r.ok()) return r.status();
    return r->structure().id();
  }
};

// Two replicas on one PostgreSQL database, uploads to one and queries to the other running all the
// while; PostgreSQL stops (a fast shutdown, as an operator's restart does) and starts again on the
// same port. Meanwhile every failed call is UNAVAILABLE; afterwards both replicas, never restarted,
// answer again, and every upload they acknowledged is stored.
TEST_F(StoreFaultsTest, PostgresDownAndBackIsUnavailableMeanwhileAndLosesNothingAcknowledged) {
  PostgresProcess pg;
  ASSERT_EQ(pg.start(), "");
  ASSERT_EQ(ensure_postgres_database(pg, "outage"), "");
  const std::string uri = "postgresql://" + std::string(PostgresProcess::kUser) +
                          "@127.0.0.1:" + std::to_string(pg.port()) + "/outage?connect_timeout=2";
  auto replica = [&](const std::string& id) {
    auto p =
        std::make_unique<SoiqdProcess>(dir_.file(id + ".db"),  // the folder of its log; the store is --db
                                       std::vector<std::string>{"--db", uri, "--replica-id", id, "--workers", "2"});
    EXPECT_FALSE(p->address().empty()) << "replica " << id << " did not start:\n" << p->log();
    return p;
  };
  std::unique_ptr<SoiqdProcess> a = replica("A"), b = replica("B");
  ASSERT_TRUE(a->running() && b->running());
  client::Client to_a = client_to(*a), to_b = client_to(*b);

  std::mutex mutex;
  std::set<int64_t> acknowledged;
  std::map<std::string, int> failures;  // "code: message" of every failed call, counted
  auto note_failure = [&](const Status& s) {
    std::lock_guard<std::mutex> lock(mutex);
    ++failures[std::string(status_code_name(s.code())) + ": " + s.message().substr(0, 200)];
  };
  for (int i = 0; i < 5; ++i) {
    Result<int64_t> id = upload_to(to_a, i, "before");
    ASSERT_TRUE(id.ok()) << id.status().to_string();
    acknowledged.insert(*id);
  }

  std::atomic<bool> stop{false};
  std::atomic<int> uploads_ok{0}, queries_ok{0};
  std::thread uploader([&] {
    for (int i = 100; !stop; ++i) {
      Result<int64_t> id = upload_to(to_a, i, "during");
      if (id.ok()) {
        std::lock_guard<std::mutex> lock(mutex);
        acknowledged.insert(*id);
        ++uploads_ok;
      } else {
        note_failure(id.status());
        std::this_thread::sleep_for(milliseconds(50));
      }
    }
  });
  std::thread querier([&] {
    while (!stop) {
      client::QueryHandlers h;
      h.on_row = [](const v1::QueryRow&) { return true; };
      Result<v1::QuerySummary> s = to_b.query(volume_query(), h);
      if (s.ok() && s->failed() == 0) {
        ++queries_ok;
      } else {
        note_failure(s.ok() ? Status(StatusCode::kUnavailable, "rows failed: " + std::to_string(s->failed()))
                            : s.status());
        std::this_thread::sleep_for(milliseconds(50));
      }
    }
  });

  // Some calls succeed before the outage, then PostgreSQL goes down for three seconds.
  const auto until = steady_clock::now() + std::chrono::seconds(60);
  while ((uploads_ok < 3 || queries_ok < 3) && steady_clock::now() < until)
    std::this_thread::sleep_for(milliseconds(20));
  ASSERT_GE(uploads_ok, 3);
  pg.stop();
  std::this_thread::sleep_for(std::chrono::seconds(3));
  {
    // While it is down, a plain read on either replica says so.
    Result<std::set<int64_t>> ids = listed_ids(to_a);
    ASSERT_FALSE(ids.ok());
    EXPECT_EQ(ids.status().code(), StatusCode::kUnavailable) << ids.status().to_string();
  }
  const int uploads_before_restart = uploads_ok, queries_before_restart = queries_ok;
  ASSERT_EQ(pg.restart(), "");

  // Back: both replicas answer again by themselves (bounded), uploads and queries go on.
  const auto recovered_by = steady_clock::now() + std::chrono::seconds(60);
  while ((uploads_ok < uploads_before_restart + 3 || queries_ok < queries_before_restart + 3) &&
         steady_clock::now() < recovered_by)
    std::this_thread::sleep_for(milliseconds(50));
  stop = true;
  uploader.join();
  querier.join();
  EXPECT_GE(uploads_ok, uploads_before_restart + 3) << "uploads did not recover";
  EXPECT_GE(queries_ok, queries_before_restart + 3) << "queries did not recover";
  EXPECT_TRUE(a->running() && b->running());

  // Every failure said UNAVAILABLE, and there were some: the outage was seen, not slept through.
  int failed = 0;
  for (const auto& [what, n] : failures) {
    failed += n;
    EXPECT_EQ(what.rfind("UNAVAILABLE: ", 0), 0u) << n << "x " << what;
  }
  EXPECT_GT(failed, 0);

  // Nothing acknowledged is lost, as either replica lists it.
  for (client::Client* c : {&to_a, &to_b}) {
    Result<std::set<int64_t>> ids = listed_ids(*c);
    ASSERT_TRUE(ids.ok()) << ids.status().to_string();
    for (int64_t id : acknowledged) EXPECT_TRUE(ids->count(id)) << "acknowledged structure " << id << " is gone";
  }
  EXPECT_EQ(a->terminate(), 0) << a->log();
  EXPECT_EQ(b->terminate(), 0) << b->log();
}

// A SQLite store on a 4 MiB tmpfs, filled by uploads: the upload that does not fit is
// RESOURCE_EXHAUSTED naming the store; soiqd keeps serving; what it acknowledged reads back whole
// (soiq-admin verify checks every blob's checksum), before and after a restart; once space is freed
// on that disk, uploads and deletes work again.
TEST_F(StoreFaultsTest, AFullDiskIsResourceExhaustedNamingTheStoreAndLosesNothingAcknowledged) {
  if (::geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
  const std::filesystem::path disk = dir_.path() / "disk";
  std::filesystem::create_directories(disk);
  ASSERT_EQ(::mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=4m,mode=0700"), 0)
      << "mount tmpfs: " << std::strerror(errno);
  struct Unmount {
    std::filesystem::path at;
    ~Unmount() { ::umount2(at.c_str(), MNT_DETACH); }
  } unmount{disk};
  const std::string store = (disk / "soiq.db").string();
  // Space the operator can free later: 512 KiB of the 4 MiB.
  const std::filesystem::path ballast = disk / "ballast";
  {
    std::ofstream out(ballast, std::ios::binary);
    out << std::string(512 << 10, '\0');
  }
  auto start_soiqd = [&] {
    // Its log and port file stay off the full disk (the folder of the first argument).
    return std::make_unique<SoiqdProcess>(dir_.file("soiqd.db"), std::vector<std::string>{"--db", store});
  };
  std::unique_ptr<SoiqdProcess> server = start_soiqd();
  ASSERT_TRUE(server->running()) << server->log();
  client::Client c = client_to(*server);

  std::map<int64_t, std::string> acknowledged;  // id -> patient
  Status full;
  for (int i = 0; i < 2000 && full.ok(); ++i) {
    const std::string patient = "P" + std::to_string(i % 10);
    Result<int64_t> id = upload_to(c, i, patient);
    if (id.ok()) {
      acknowledged[*id] = patient;
    } else {
      full = id.status();
    }
  }
  ASSERT_FALSE(full.ok()) << "4 MiB took " << acknowledged.size() << " uploads and did not fill";
  ASSERT_GT(acknowledged.size(), 10u);
  EXPECT_EQ(full.code(), StatusCode::kResourceExhausted) << full.to_string();
  EXPECT_NE(full.message().find(store), std::string::npos) << full.to_string();

  // Still serving, everything acknowledged listed, and a query over it all computes every row.
  auto everything_is_there = [&](const client::Client& to) {
    Result<std::set<int64_t>> ids = listed_ids(to);
    ASSERT_TRUE(ids.ok()) << ids.status().to_string();
    for (const auto& [id, patient] : acknowledged)
      EXPECT_TRUE(ids->count(id)) << "acknowledged structure " << id << " of " << patient << " is gone";
    client::QueryHandlers h;
    int rows = 0;
    h.on_row = [&](const v1::QueryRow&) {
      ++rows;
      return true;
    };
    Result<v1::QuerySummary> s = to.query(volume_query(), h);
    ASSERT_TRUE(s.ok()) << s.status().to_string();
    EXPECT_EQ(s->failed(), 0);
    EXPECT_EQ(rows, int(ids->size()));
  };
  everything_is_there(c);

  // On a full disk even a delete may not fit (SQLite writes it ahead first): it fails as cleanly.
  if (Result<v1::DeleteResponse> d = c.delete_patient("P0"); !d.ok()) {
    EXPECT_EQ(d.status().code(), StatusCode::kResourceExhausted) << d.status().to_string();
    everything_is_there(c);
  } else {
    std::erase_if(acknowledged, [](const auto& entry) { return entry.second == "P0"; });
  }

  // The operator frees space on that disk: soiqd takes uploads again, without a restart.
  std::filesystem::remove(ballast);
  Result<int64_t> again = upload_to(c, 5000, "after");
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  acknowledged[*again] = "after";
  ASSERT_TRUE(c.delete_patient("P1").ok());
  std::erase_if(acknowledged, [](const auto& entry) { return entry.second == "P1"; });
  everything_is_there(c);

  // After a clean stop the store verifies whole, and a restarted soiqd serves all of it.
  ASSERT_EQ(server->terminate(), 0) << server->log();
  const std::string verify_log = dir_.file("verify.log");
  EXPECT_EQ(run_to_exit({SOIQ_ADMIN_BINARY, "verify", "--db", store}, verify_log), 0) << read_text(verify_log);
  server = start_soiqd();
  ASSERT_TRUE(server->running()) << server->log();
  client::Client after = client_to(*server);
  everything_is_there(after);
}

}  // namespace
}  // namespace soiq::testing
