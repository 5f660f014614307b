#include "server/app/precompute_worker.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>

#include "core/features/feature_catalogue.h"
#include "server/util/log.h"

namespace soiq::server {
namespace {

// The intensity features of the default set, and their regions: inside, and the 3 mm shell around
// the structure (the tissue next to it, the paper's motivating question). The shell costs little
// beside the conversion (BENCHMARKS.md, "where the cold time goes") and, with the grid's cache key
// independent of its margin (grid_choice.h), serves every query on the default grid that asks it.
const std::vector<std::string> kIntensityNames = {"mean", "minimum", "maximum"};
const std::vector<RegionSpec> kIntensityRegions = {RegionSpec{}, RegionSpec{RegionKind::kShell, 3}};

// The weighted set's region: weighted intensities are defined inside only (structure_features.h).
const std::vector<RegionSpec> kWeightedRegions = {RegionSpec{}};

// Every coverage-weighted name: one coverage conversion gives them all, so naming fewer would save
// nothing and leave a query naming another one to convert again. Without images, the volume alone.
std::vector<std::string> weighted_names(bool with_images) {
  std::vector<std::string> names;
  for (const std::string& n : weighted_feature_names())
    if (with_images || find_intensity_feature(n) == nullptr) names.push_back(n);
  return names;
}

void log_image_failed(const db::StructureRecord& structure, const std::string& series, const Status& error) {
  log_event("warn", {{"event", "precompute_image_failed"},
                     {"structure", std::to_string(structure.id)},
                     {"series", series},
                     {"error", error.to_string()}});
}

// The weighted set's failures apart: the default values of the same image may well be stored.
void log_weighted_failed(const db::StructureRecord& structure, const std::string& series, const Status& error) {
  log_event("warn", {{"event", "precompute_weighted_failed"},
                     {"structure", std::to_string(structure.id)},
                     {"series", series},
                     {"error", error.to_string()}});
}

// Structures read from the queue at once: few, so that a structure deleted or replaced meanwhile
// costs little, and a stop is quick.
constexpr int64_t kBatch = 16;

// The thread looks at the queue this often even without notify() (a write by another process on the
// same database, a failure to write).
constexpr auto kPoll = std::chrono::seconds(5);

// Nice 19: beside busy threads of normal priority the thread gets about 1.5 % of a core, so queries
// and uploads barely notice it, yet it is never starved outright. (SCHED_IDLE would starve it for
// as long as anything else runs, and a conversion it had started would hold its memory reservation,
// or a write transaction, meanwhile.) Best effort: without it the thread runs as any other.
void lower_priority() { (void)setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), 19); }

}  // namespace

PrecomputeWorker::~PrecomputeWorker() {
  stopping_ = true;
  notify();
  if (!thread_.joinable()) return;
  thread_.join();
  log_event("info", {{"event", "precompute_stopped"}, {"structures_precomputed", std::to_string(stored_.load())}});
}

Status PrecomputeWorker::start() {
  SOIQ_ASSIGN_OR_RETURN(const int64_t stale, store_.requeue_precompute(feature_definitions_version(), set_));
  if (stale > 0) {
    log_event("info", {{"event", "precompute_requeued"},
                       {"structures", std::to_string(stale)},
                       {"why", set_ == db::PrecomputedSet::kDefault
                                   ? "feature definitions changed"
                                   : "feature definitions changed, or values stored without the weighted set"}});
  }
  thread_ = std::thread([this] { loop(); });
  return ok_status();
}

void PrecomputeWorker::notify() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    work_signalled_ = true;
  }
  wake_.notify_all();
}

Result<FeatureValues> PrecomputeWorker::values(const db::StructureRecord& structure,
                                               const std::vector<db::SeriesRecord>& series, FeatureAsk ask,
                                               db::Precomputed& out) {
  SOIQ_RETURN_IF_ERROR(complete_feature_ask(ask));
  SOIQ_ASSIGN_OR_RETURN(const FeaturePlan plan, features_.plan(structure, series, ask));
  Result<std::vector<db::CachedFeature>> cached = store_.cached_features({plan.cache_key});
  if (!cached.ok()) {
    return Status(cached.status().code(),
                  "structure " + std::to_string(structure.id) + ": " + cached.status().message());
  }
  FeatureValues have;
  for (db::CachedFeature& e : *cached) have[e.entry] = std::move(e.value);
  const bool complete =
      std::all_of(plan.wants.begin(), plan.wants.end(), [&](const WantedValue& w) { return have.count(w.entry) > 0; });
  if (complete) return have;
  db::SurfaceFeatures computed;
  SOIQ_ASSIGN_OR_RETURN(FeatureValues v, features_.compute(plan, ask, &stopping_, &computed));
  for (db::CachedFeature& e : computed.entries) out.cache_entries.push_back(std::move(e));
  return v;
}

Status PrecomputeWorker::weighted_values(const db::StructureRecord& structure,
                                         const std::vector<db::SeriesRecord>& series, db::Precomputed& out) {
  // An open surface has no inside every line agrees on, hence no fractions (FAILED_PRECONDITION
  // each time): a query naming them meets that error itself.
  if (structure.robust) return ok_status();
  FeatureAsk all;
  all.names = weighted_names(!series.empty());
  all.regions = kWeightedRegions;
  for (const db::SeriesRecord& s : series) all.images.push_back(s.series_uid);
  const Result<FeatureValues> v = values(structure, series, all, out);
  if (stopping_) return Status(StatusCode::kCancelled, "soiqd is stopping");
  if (v.ok()) return ok_status();
  if (series.size() <= 1) {
    log_weighted_failed(structure, series.empty() ? "" : series[0].series_uid, v.status());
    return ok_status();
  }
  // As for the default set: one bad image costs only its own values.
  for (const db::SeriesRecord& s : series) {
    FeatureAsk one = all;
    one.images = {s.series_uid};
    const Result<FeatureValues> w = values(structure, series, one, out);
    if (stopping_) return Status(StatusCode::kCancelled, "soiqd is stopping");
    if (!w.ok()) log_weighted_failed(structure, s.series_uid, w.status());
  }
  return ok_status();
}

Result<db::Precomputed> PrecomputeWorker::precompute(const db::StructureRecord& structure) {
  db::Precomputed out;
  out.structure_id = structure.id;
  out.surface_sha256 = structure.surface.sha256;
  out.definitions_version = feature_definitions_version();
  out.set = set_;
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, store_.list_series(structure.study_uid));

  FeatureAsk shape;
  shape.names = db::stored_feature_names();
  // Every image at once first (one conversion); if that fails, the shape alone and then each image
  // alone, so that one bad image costs only its own values.
  Result<FeatureValues> shape_values = Status(StatusCode::kNotFound, "no image");
  Status images_failed = ok_status();
  if (!series.empty()) {
    FeatureAsk all = shape;
    all.names.insert(all.names.end(), kIntensityNames.begin(), kIntensityNames.end());
    for (const db::SeriesRecord& s : series) all.images.push_back(s.series_uid);
    all.regions = kIntensityRegions;
    shape_values = values(structure, series, all, out);
    if (stopping_) return Status(StatusCode::kCancelled, "soiqd is stopping");
    if (!shape_values.ok()) images_failed = shape_values.status();
  }
  if (!shape_values.ok()) {
    shape_values = values(structure, series, shape, out);
    if (stopping_) return Status(StatusCode::kCancelled, "soiqd is stopping");
    if (!shape_values.ok()) {
      out.failure = shape_values.status().to_string();
      return out;
    }
    for (size_t i = 0; i < series.size() && series.size() > 1; ++i) {
      FeatureAsk one;
      one.names = kIntensityNames;
      one.regions = kIntensityRegions;
      one.images = {series[i].series_uid};
      const Result<FeatureValues> v = values(structure, series, one, out);
      if (stopping_) return Status(StatusCode::kCancelled, "soiqd is stopping");
      if (!v.ok()) log_image_failed(structure, series[i].series_uid, v.status());
    }
    if (series.size() == 1) log_image_failed(structure, series[0].series_uid, images_failed);
  }
  if (set_ == db::PrecomputedSet::kWithWeighted) SOIQ_RETURN_IF_ERROR(weighted_values(structure, series, out));
  for (const std::string& name : db::stored_feature_names()) {
    const auto it = shape_values->find(feature_entry(name, "", "", Interpolation::kNearest));
    if (it == shape_values->end() || it->second.size() != 1) {
      out.values.push_back(std::nullopt);
    } else {
      out.values.push_back(it->second[0]);
    }
  }
  return out;
}

void PrecomputeWorker::loop() {
  lower_priority();
  auto sleep = [&] {
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait_for(lock, kPoll, [&] { return work_signalled_ || stopping_.load(); });
    work_signalled_ = false;
  };
  while (!stopping_) {
    if (!may_run_()) {  // another replica precomputes
      sleep();
      continue;
    }
    Result<std::vector<db::StructureRecord>> batch = store_.precompute_queue(kBatch);
    if (!batch.ok()) {
      log_event("warn", {{"event", "precompute_queue_unreadable"}, {"error", batch.status().to_string()}});
      sleep();
      continue;
    }
    if (batch->empty()) {
      sleep();
      continue;
    }
    // The batch's results go to the store in one transaction (one sync to disk, not sixteen).
    std::vector<db::Precomputed> results;
    for (const db::StructureRecord& s : *batch) {
      if (stopping_) break;
      Result<db::Precomputed> done = precompute(s);
      if (stopping_) break;
      if (!done.ok()) {
        // The store could not be read for it: a failure like any other, so the queue moves on.
        db::Precomputed failed;
        failed.structure_id = s.id;
        failed.surface_sha256 = s.surface.sha256;
        failed.failure = done.status().to_string();
        done = std::move(failed);
      }
      if (!done->failure.empty()) {
        log_event("warn",
                  {{"event", "precompute_failed"}, {"structure", std::to_string(s.id)}, {"error", done->failure}});
      }
      results.push_back(std::move(done).value());
    }
    // Work finished before a stop is kept; what was in flight stays queued.
    const Status stored = store_.put_precomputed(results);
    if (stored.ok()) stored_ += int64_t(results.size());
    if (!stored.ok()) {
      // A full disk, a busy database: the structures stay queued; try again after a pause.
      log_event("warn", {{"event", "precompute_not_stored"},
                         {"structures", std::to_string(results.size())},
                         {"error", stored.to_string()}});
      sleep();
    }
  }
}

}  // namespace soiq::server
