#include "server/app/shared_stage2.h"

#include <unistd.h>

#include <random>

#include "server/app/feature_ask_codec.h"
#include "server/util/log.h"

namespace soiq::server {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

constexpr milliseconds kIdlePoll{25};  // an empty queue is asked again this often
constexpr milliseconds kWaitPoll{10};  // a poster asks how much of its query is left this often
constexpr milliseconds kProgressEvery{100};

std::string random_hex(int bytes) {
  static thread_local std::mt19937_64 rng(std::random_device{}());
  std::string out;
  for (int i = 0; i < bytes; ++i) {
    char hex[3];
    std::snprintf(hex, sizeof hex, "%02x", unsigned(rng() & 0xff));
    out += hex;
  }
  return out;
}

}  // namespace

std::string default_replica_id() {
  char host[256] = {0};
  if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
  // Ids are at most 64 bytes (db/validate_records.h): a long host name is cut.
  std::string id = std::string(host).substr(0, 40) + "-" + std::to_string(getpid()) + "-" + random_hex(4);
  return id;
}

SharedStage2::~SharedStage2() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  cancelled_ = true;
  wake_.notify_all();
  if (heartbeat_.joinable()) heartbeat_.join();
  if (claimer_.joinable()) claimer_.join();
  // Items still running on the pool hold `this`: wait for them (they were told to cancel).
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait(lock, [&] { return in_flight_ == 0; });
  log_event("info", {{"event", "replica_stopped"},
                     {"replica", options_.replica_id},
                     {"items_computed", std::to_string(computed_.load())}});
}

Status SharedStage2::start() {
  SOIQ_ASSIGN_OR_RETURN(const int live, store_.replica_heartbeat(options_.replica_id, options_.live.count()));
  live_ = live;
  SOIQ_ASSIGN_OR_RETURN(const std::string first, store_.first_live_replica(options_.live.count()));
  leads_ = first == options_.replica_id;
  heartbeat_ = std::thread([this] { heartbeat_loop(); });
  claimer_ = std::thread([this] { claim_loop(); });
  log_event("info",
            {{"event", "replica_started"}, {"replica", options_.replica_id}, {"live_replicas", std::to_string(live)}});
  return ok_status();
}

bool SharedStage2::sleep_unless_stopping(milliseconds d) {
  std::unique_lock<std::mutex> lock(mutex_);
  return !wake_.wait_for(lock, d, [&] { return stopping_; });
}

void SharedStage2::heartbeat_loop() {
  while (sleep_unless_stopping(options_.live / 3)) {
    Result<int> live = store_.replica_heartbeat(options_.replica_id, options_.live.count());
    Result<std::string> first =
        live.ok() ? store_.first_live_replica(options_.live.count()) : Result<std::string>(live.status());
    if (first.ok()) {
      live_ = *live;
      leads_ = *first == options_.replica_id;
    } else {
      log_event("warn", {{"event", "heartbeat_failed"}, {"error", first.status().message()}});
    }
  }
}

void SharedStage2::claim_loop() {
  const int batch = std::max(1, pool_.size());
  while (true) {
    int free_slots = 0;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      // Claim only what this replica's workers can start: claimed items wait for no one else.
      wake_.wait(lock, [&] { return stopping_ || in_flight_ < batch; });
      if (stopping_) return;
      free_slots = batch - in_flight_;
    }
    Result<std::vector<db::Stage2Work>> items =
        store_.claim_stage2_work(options_.replica_id, free_slots, options_.live.count());
    if (!items.ok()) log_event("warn", {{"event", "stage2_claim_failed"}, {"error", items.status().message()}});
    if (!items.ok() || items->empty()) {
      if (!sleep_unless_stopping(kIdlePoll)) return;
      continue;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      in_flight_ += int(items->size());
    }
    for (db::Stage2Work& item : *items) {
      pool_.submit([this, item = std::move(item)] {
        compute(item);
        {
          std::lock_guard<std::mutex> lock(mutex_);
          --in_flight_;
        }
        wake_.notify_all();
      });
    }
  }
}

void SharedStage2::compute(const db::Stage2Work& item) {
  auto failed = [&](const Status& s) {
    // The poster computes it again and reports the failure in its query.
    log_event(
        "info",
        {{"event", "stage2_item_failed"}, {"structure", std::to_string(item.structure_id)}, {"error", s.message()}});
  };
  if (!cancelled_) {
    Result<FeatureAsk> ask = decode_feature_ask(item.ask);
    Result<db::StructureRecord> structure =
        ask.ok() ? store_.get_structure(item.structure_id) : Result<db::StructureRecord>(ask.status());
    Result<std::vector<db::SeriesRecord>> series = structure.ok()
                                                       ? store_.list_series(structure->study_uid)
                                                       : Result<std::vector<db::SeriesRecord>>(structure.status());
    Result<FeaturePlan> plan =
        series.ok() ? features_.plan(*structure, *series, *ask) : Result<FeaturePlan>(series.status());
    // Without `to_store` the engine writes every value to the shared feature cache itself.
    Result<FeatureValues> values =
        plan.ok() ? features_.compute(*plan, *ask, &cancelled_) : Result<FeatureValues>(plan.status());
    if (values.ok()) {
      ++computed_;
    } else {
      failed(values.status());
    }
  }
  if (cancelled_) return;  // shutting down: the item stays claimed, and is claimed again once we are silent
  const Status done = store_.finish_stage2_work(item.query_id, item.structure_id);
  if (!done.ok()) log_event("warn", {{"event", "stage2_finish_failed"}, {"error", done.message()}});
}

Status SharedStage2::share(const FeatureAsk& ask, const std::vector<int64_t>& structure_ids,
                           const std::function<Status()>& stop, const std::function<Status(int64_t)>& progress) {
  const std::string query_id = options_.replica_id.substr(0, 40) + "-" + random_hex(8);
  SOIQ_RETURN_IF_ERROR(store_.post_stage2_work(options_.replica_id, query_id, encode_feature_ask(ask), structure_ids));
  wake_.notify_all();
  // Whatever way this returns, nothing of the query stays queued.
  struct DropOnExit {
    db::Store& store;
    const std::string& id;
    ~DropOnExit() { (void)store.drop_stage2_work(id); }
  } drop{store_, query_id};
  const int64_t total = int64_t(structure_ids.size());
  // Items whose claimers die are claimed again within `live`; if nothing at all finishes for much
  // longer, something is wrong beyond a dead replica: stop waiting, and the query computes what is
  // left itself (it reads what was finished from the cache).
  const auto stalled_after = std::max<Clock::duration>(options_.live * 10, std::chrono::seconds(10));
  Clock::time_point last_progress = Clock::now(), last_change = Clock::now();
  int64_t last_left = total;
  while (true) {
    SOIQ_RETURN_IF_ERROR(stop());
    SOIQ_ASSIGN_OR_RETURN(const int64_t left, store_.stage2_work_left(query_id));
    if (left == 0 || Clock::now() - last_progress >= kProgressEvery) {
      SOIQ_RETURN_IF_ERROR(progress(total - left));
      last_progress = Clock::now();
    }
    if (left == 0) return ok_status();
    if (left != last_left) last_left = left, last_change = Clock::now();
    if (Clock::now() - last_change > stalled_after) {
      log_event("warn", {{"event", "stage2_sharing_stalled"}, {"query", query_id}, {"left", std::to_string(left)}});
      return ok_status();
    }
    std::this_thread::sleep_for(kWaitPoll);
  }
}

}  // namespace soiq::server
