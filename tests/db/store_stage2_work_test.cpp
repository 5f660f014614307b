// Replicas sharing stage 2 through the Store, on every backend: heartbeats, and the stage-2 work
// queue (post, claim, finish, what a dead replica leaves). Liveness is by the database's clock;
// the tests wait real milliseconds for a replica to fall silent.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"

namespace soiq::db {
namespace {

using namespace std::chrono_literals;

template <typename Backend>
class StoreStage2Work : public testing::StoreTest<Backend> {
 protected:
  int beat(const std::string& replica, int64_t live_ms = 60000) {
    Result<int> live = this->replicas().replica_heartbeat(replica, live_ms);
    EXPECT_TRUE(live.ok()) << live.status().to_string();
    return live.ok() ? *live : -1;
  }
  std::vector<Stage2Work> claim(const std::string& replica, int64_t limit, int64_t live_ms = 60000) {
    auto got = this->replicas().claim_stage2_work(replica, limit, live_ms);
    EXPECT_TRUE(got.ok()) << got.status().to_string();
    return got.ok() ? *got : std::vector<Stage2Work>{};
  }
  int64_t left(const std::string& query) {
    auto n = this->replicas().stage2_work_left(query);
    EXPECT_TRUE(n.ok()) << n.status().to_string();
    return n.ok() ? *n : -1;
  }
};
TYPED_TEST_SUITE(StoreStage2Work, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreStage2Work, AHeartbeatCountsTheReplicasHeardFromWithinTheWindow) {
  EXPECT_EQ(this->beat("a"), 1);
  EXPECT_EQ(this->beat("b"), 2);
  EXPECT_EQ(this->beat("a"), 2);  // again: still two
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(this->beat("c", 200), 1);  // a and b are silent for longer than 200 ms
  EXPECT_EQ(this->beat("a", 60000), 3);
}

TYPED_TEST(StoreStage2Work, TheFirstLiveReplicaIsTheSmallestIdHeardFrom) {
  EXPECT_EQ(*this->replicas().first_live_replica(60000), "");
  this->beat("b");
  this->beat("c");
  EXPECT_EQ(*this->replicas().first_live_replica(60000), "b");
  this->beat("a");
  EXPECT_EQ(*this->replicas().first_live_replica(60000), "a");
  std::this_thread::sleep_for(300ms);
  this->beat("c");
  EXPECT_EQ(*this->replicas().first_live_replica(200), "c");  // a and b are silent
}

TYPED_TEST(StoreStage2Work, EveryPostedItemIsClaimedOnceAndFinishedItemsAreNotLeft) {
  this->beat("a");
  this->beat("b");
  std::vector<int64_t> ids;
  for (int64_t i = 1; i <= 300; ++i) ids.push_back(i);  // more than one statement's list
  ids.push_back(7);                                     // twice: one item
  ASSERT_TRUE(this->replicas().post_stage2_work("a", "q1", "ask one", ids).ok());
  EXPECT_EQ(this->left("q1"), 300);
  const std::vector<Stage2Work> first = this->claim("a", 120);
  const std::vector<Stage2Work> second = this->claim("b", 1000);
  ASSERT_EQ(first.size(), 120u);
  ASSERT_EQ(second.size(), 180u);
  EXPECT_TRUE(this->claim("b", 10).empty());  // all held by live replicas
  std::set<int64_t> claimed;
  for (const auto* part : {&first, &second}) {
    for (const Stage2Work& w : *part) {
      EXPECT_EQ(w.query_id, "q1");
      EXPECT_EQ(w.ask, "ask one");
      EXPECT_TRUE(claimed.insert(w.structure_id).second) << w.structure_id << " claimed twice";
    }
  }
  EXPECT_EQ(claimed.size(), 300u);
  for (const Stage2Work& w : first) ASSERT_TRUE(this->replicas().finish_stage2_work(w.query_id, w.structure_id).ok());
  EXPECT_EQ(this->left("q1"), 180);
  EXPECT_TRUE(this->replicas().finish_stage2_work("q1", 1).ok());  // finished before: no error
  ASSERT_TRUE(this->replicas().drop_stage2_work("q1").ok());
  EXPECT_EQ(this->left("q1"), 0);
}

TYPED_TEST(StoreStage2Work, ADeadReplicasClaimsAreClaimedAgainAndItsPostsDropped) {
  this->beat("poster");
  this->beat("dies");
  ASSERT_TRUE(this->replicas().post_stage2_work("poster", "q", "ask", {1, 2, 3}).ok());
  ASSERT_TRUE(this->replicas().post_stage2_work("dies", "orphan", "ask", {4}).ok());
  ASSERT_EQ(this->claim("dies", 3).size(), 3u);  // q's 1, 2, 3 (posted first)
  std::this_thread::sleep_for(300ms);
  this->beat("poster", 200);  // "dies" has been silent for 300 ms: dead; its own post is dropped
  EXPECT_EQ(this->left("orphan"), 0);
  const std::vector<Stage2Work> again = this->claim("poster", 10, 200);
  ASSERT_EQ(again.size(), 3u);
  for (int64_t i = 0; i < 3; ++i) EXPECT_EQ(again[size_t(i)].structure_id, i + 1);
}

TYPED_TEST(StoreStage2Work, ReplicasClaimingAtOnceNeverShareAnItem) {
  std::vector<int64_t> ids;
  for (int64_t i = 1; i <= 400; ++i) ids.push_back(i);
  for (const char* r : {"r0", "r1", "r2", "r3"}) this->beat(r);
  ASSERT_TRUE(this->replicas().post_stage2_work("r0", "q", "ask", ids).ok());
  std::mutex mutex;
  std::map<int64_t, int> times;
  std::atomic<int> failures{0};
  std::vector<std::thread> replicas;
  for (int r = 0; r < 4; ++r) {
    replicas.emplace_back([&, r] {
      const std::string id = "r" + std::to_string(r);
      for (int round = 0; round < 400; ++round) {  // bounded: a broken claim must fail, not hang
        auto got = this->replicas().claim_stage2_work(id, 7, 60000);
        if (!got.ok()) {
          ++failures;
          return;
        }
        if (got->empty()) return;
        if (got->size() > 7) ++failures;  // a claim never takes more than it asked for
        std::lock_guard<std::mutex> lock(mutex);
        for (const Stage2Work& w : *got) ++times[w.structure_id];
      }
    });
  }
  for (std::thread& t : replicas) t.join();
  EXPECT_EQ(failures.load(), 0);
  ASSERT_EQ(times.size(), 400u);
  for (const auto& [id, n] : times) EXPECT_EQ(n, 1) << "item " << id;
}

TYPED_TEST(StoreStage2Work, BadIdsAreInvalidArguments) {
  EXPECT_EQ(this->replicas().replica_heartbeat("", 1000).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(this->replicas().replica_heartbeat("a\nb", 1000).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(this->replicas().post_stage2_work("a", "", "ask", {1}).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(this->replicas().claim_stage2_work("a", 0, 1000).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq::db
