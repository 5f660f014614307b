#include "server/app/query_engine.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "server/app/query_cached_values.h"
#include "server/app/query_skips.h"
#include "server/app/query_subjects.h"
#include "server/util/log.h"

namespace soiq::server {
namespace {

using Clock = std::chrono::steady_clock;
using query_run::CachedValues;
using query_run::candidate_scalar;
using query_run::candidate_value;
using query_run::Completions;
using query_run::Computed;
using query_run::read_cached_values;
using query_run::Subject;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// The images a query names: its intensity features' and its grid's, when the grid is a series.
std::vector<std::string> image_refs(const FeatureAsk& ask) {
  std::vector<std::string> refs = ask.images;
  if (ask.grid.kind != GridChoice::Kind::kAxisAligned) refs.push_back(ask.grid.series);
  return refs;
}

// One run of one query: the steps of query_engine.h, in order, over shared state.
class QueryRun {
 public:
  QueryRun(const Query& q, db::Store& store, FeatureEngine& features, WorkerPool& pool, SharedStage2* sharing,
           ImageRefsCheck& image_refs, const std::function<Status()>& stop, const QueryOutput& out)
      : q_(q),
        store_(store),
        features_(features),
        pool_(pool),
        sharing_(sharing),
        image_refs_(image_refs),
        stop_(stop),
        out_(out) {}

  Result<QuerySummary> run(int64_t stage1_cap) {
    const Clock::time_point start = Clock::now();
    SOIQ_RETURN_IF_ERROR(image_refs_.check(store_, image_refs(q_.ask)));
    db::Stage1Filter stage1 = q_.stage1;
    stage1.stored_features = stored_feature_conditions(q_);
    SOIQ_ASSIGN_OR_RETURN(candidates_, store_.stage1(stage1, stage1_cap));
    summary_.stage1_candidates = int64_t(candidates_.size());
    summary_.stage1_ms = ms_since(start);
    const Clock::time_point stage2_start = Clock::now();
    SOIQ_RETURN_IF_ERROR(progress("stage1", summary_.stage1_candidates));
    add_subjects();
    SOIQ_ASSIGN_OR_RETURN(const std::vector<size_t> misses, plan_and_read_cache());
    for (size_t i = 0; i < candidates_.size() && !enough_; ++i) SOIQ_RETURN_IF_ERROR(evaluate(i));
    SOIQ_RETURN_IF_ERROR(compute(misses));
    SOIQ_RETURN_IF_ERROR(stream_ordered());
    summary_.skipped = skips_.groups();
    summary_.stage2_ms = ms_since(stage2_start);
    summary_.total_ms = ms_since(start);
    return summary_;
  }

 private:
  Status progress(const char* stage, int64_t done) {
    return out_.progress(QueryProgress{stage, done, int64_t(candidates_.size())});
  }

  // Candidates and their twins, each structure once.
  void add_subjects() {
    auto add = [&](const db::StructureRecord& s, size_t candidate) {
      auto [it, fresh] = subject_of_.emplace(s.id, subjects_.size());
      if (fresh) subjects_.push_back(Subject{s, std::nullopt, ok_status(), nullptr, {}, false, {}});
      subjects_[it->second].dependents.push_back(candidate);
      return it->second;
    };
    own_.resize(candidates_.size());
    twin_.resize(candidates_.size());
    evaluated_.assign(candidates_.size(), false);
    for (size_t i = 0; i < candidates_.size(); ++i) own_[i] = add(candidates_[i].structure, i);
    for (size_t i = 0; i < candidates_.size(); ++i)
      if (candidates_[i].twin) twin_[i] = add(*candidates_[i].twin, i);
  }

  // Each subject's plan, then the cache for every plan in one round trip. Subjects answered by the
  // cache (or that cannot be planned) are ready; the others are returned, to compute.
  Result<std::vector<size_t>> plan_and_read_cache() {
    std::vector<size_t> planned;
    if (!q_.ask.names.empty()) SOIQ_RETURN_IF_ERROR(read_study_series());
    for (size_t i = 0; i < subjects_.size(); ++i) {
      Subject& s = subjects_[i];
      if (q_.ask.names.empty()) {
        s.ready = true;
        continue;
      }
      SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord>* series, study_series(s.structure.study_uid));
      Result<FeaturePlan> plan = features_.plan(s.structure, *series, q_.ask);
      if (!plan.ok()) {
        s.error = plan.status();
        s.ready = true;
        continue;
      }
      s.plan = std::move(plan).value();
      planned.push_back(i);
    }
    SOIQ_ASSIGN_OR_RETURN(CachedValues cached, read_cached_values(store_, subjects_, planned));
    for (auto& [i, error] : cached.damaged) {
      subjects_[i].error = std::move(error);
      subjects_[i].ready = true;
    }
    std::vector<size_t> misses;
    for (size_t i : planned) {
      Subject& s = subjects_[i];
      if (s.ready) continue;  // its stored values are damaged
      std::shared_ptr<const FeatureValues> have = all_wanted(cached, s);
      if (!have) {
        misses.push_back(i);
        continue;
      }
      set_values(s, std::move(have));
      s.ready = true;
      ++summary_.cache_hits;
    }
    return misses;
  }

  // The cached values of the subject's key when they hold every value its plan wants, else null.
  static std::shared_ptr<const FeatureValues> all_wanted(const CachedValues& cached, const Subject& s) {
    auto it = cached.by_key.find(s.plan->cache_key);
    if (it == cached.by_key.end()) return nullptr;
    const FeatureValues& have = *it->second;
    const bool all = std::all_of(s.plan->wants.begin(), s.plan->wants.end(),
                                 [&](const WantedValue& w) { return have.count(w.entry) > 0; });
    return all ? it->second : nullptr;
  }

  // The subject's values, and each query feature's among them.
  void set_values(Subject& s, std::shared_ptr<const FeatureValues> values) {
    s.values = std::move(values);
    s.asked.assign(q_.features.size(), nullptr);
    for (size_t f = 0; f < q_.features.size(); ++f) {
      const QueryFeature& feature = q_.features[f];
      std::string entry = feature.name;
      if (feature.intensity) {
        const auto& images = q_.ask.images;
        const size_t image = std::find(images.begin(), images.end(), feature.image) - images.begin();
        // Two names of one series (modality and uid) share it in the plan: the plan maps each name.
        const db::SeriesRecord& series = s.plan->images.at(s.plan->image_of_ask.at(image));
        entry = feature_entry(feature.name, region_name(feature.region), series.sha256, q_.ask.interpolation);
      }
      auto it = s.values->find(entry);
      if (it != s.values->end()) s.asked[f] = &it->second;
    }
  }

  // The misses computed by every live replica (shared_stage2.h), then read back from the shared
  // cache and evaluated; those still missing (they failed elsewhere) are returned, to compute here,
  // where they fail again and are reported as in a single replica's run.
  Result<std::vector<size_t>> share(const std::vector<size_t>& misses) {
    std::vector<int64_t> ids;
    for (size_t i : misses) ids.push_back(subjects_[i].structure.id);
    const int64_t candidates = int64_t(candidates_.size());
    SOIQ_RETURN_IF_ERROR(sharing_->share(q_.ask, ids, stop_, [&](int64_t finished) {
      return progress("stage2", std::min(candidates, done_ + finished));
    }));
    SOIQ_ASSIGN_OR_RETURN(CachedValues cached, read_cached_values(store_, subjects_, misses));
    for (auto& [i, error] : cached.damaged) SOIQ_RETURN_IF_ERROR(complete(i, std::move(error)));
    std::vector<size_t> left;
    for (size_t i : misses) {
      if (subjects_[i].ready) continue;  // its stored values are damaged
      std::shared_ptr<const FeatureValues> have = all_wanted(cached, subjects_[i]);
      if (!have) {
        left.push_back(i);
        continue;
      }
      ++summary_.shared;
      ++summary_.computed;  // now, by one of the replicas
      SOIQ_RETURN_IF_ERROR(complete_with(i, std::move(have)));
      if (enough_) break;
    }
    return left;
  }

  // Every subject's study's series, in one read.
  Status read_study_series() {
    std::vector<std::string> uids;
    for (const Subject& s : subjects_) uids.push_back(s.structure.study_uid);  // the store reads each once
    SOIQ_ASSIGN_OR_RETURN(series_of_, store_.series_of_studies(uids));
    return ok_status();
  }

  // A study's series (read_study_series read them); NOT_FOUND for a study deleted since stage 1.
  Result<const std::vector<db::SeriesRecord>*> study_series(const std::string& uid) {
    auto it = series_of_.find(uid);
    if (it == series_of_.end()) return not_found("study '" + uid + "' not found");
    return &it->second;
  }

  // The misses on the worker pool (first across the replicas, when others are live); each candidate
  // is evaluated as its subjects complete.
  Status compute(std::vector<size_t> misses) {
    if (!enough_ && sharing_ != nullptr && sharing_->live_replicas() > 1 && misses.size() > 1) {
      SOIQ_ASSIGN_OR_RETURN(misses, share(misses));
    }
    auto completions = std::make_shared<Completions>();
    // Whatever way this returns, workers not yet started skip their structure.
    struct CancelOnExit {
      Completions& c;
      ~CancelOnExit() { c.cancelled = true; }
    } cancel_on_exit{*completions};
    size_t pending = enough_ ? 0 : submit(misses, completions);
    Clock::time_point last_progress = Clock::now();
    while (pending > 0 && !enough_) {
      std::deque<Computed> batch;
      {
        std::unique_lock<std::mutex> lock(completions->mutex);
        completions->wake.wait_for(lock, std::chrono::milliseconds(50), [&] { return !completions->done.empty(); });
        batch.swap(completions->done);
      }
      SOIQ_RETURN_IF_ERROR(stop_());
      // What the workers computed since the last round goes to the cache in one transaction, here
      // and not on the workers: one writer, one commit, and the workers go on converting.
      std::vector<db::SurfaceFeatures> to_store;
      for (Computed& c : batch) {
        --pending;
        if (!c.to_store.entries.empty()) to_store.push_back(std::move(c.to_store));
        SOIQ_RETURN_IF_ERROR(complete(c.idx, std::move(c.values)));
      }
      store_cache(to_store);
      if (ms_since(last_progress) >= 100 || pending == 0) {
        SOIQ_RETURN_IF_ERROR(progress("stage2", done_));
        last_progress = Clock::now();
      }
    }
    if (misses.empty() || enough_) SOIQ_RETURN_IF_ERROR(progress("stage2", done_));
    return ok_status();
  }

  // The answer does not depend on the cache: a failed write (a full disk) is logged, and the query
  // goes on with the values it has.
  void store_cache(const std::vector<db::SurfaceFeatures>& batch) {
    if (batch.empty()) return;
    const Status s = store_.put_cached_features(batch);
    if (!s.ok()) {
      log_event("warn", {{"event", "feature_cache_write_failed"},
                         {"structures", std::to_string(batch.size())},
                         {"error", s.message()}});
    }
  }

  size_t submit(const std::vector<size_t>& misses, const std::shared_ptr<Completions>& completions) {
    auto ask = std::make_shared<const FeatureAsk>(q_.ask);
    FeatureEngine* engine = &features_;
    for (size_t idx : misses) {
      auto plan = std::make_shared<const FeaturePlan>(*subjects_[idx].plan);
      pool_.submit([completions, ask, plan, engine, idx] {
        db::SurfaceFeatures to_store;
        Result<FeatureValues> r = completions->cancelled.load()
                                      ? Result<FeatureValues>(Status(StatusCode::kCancelled, "cancelled"))
                                      : engine->compute(*plan, *ask, &completions->cancelled, &to_store);
        std::lock_guard<std::mutex> lock(completions->mutex);
        completions->done.push_back(Computed{idx, std::move(r), std::move(to_store)});
        completions->wake.notify_one();
      });
    }
    return misses.size();
  }

  // A subject computed here (or failed).
  Status complete(size_t idx, Result<FeatureValues> result) {
    if (!result.ok()) {
      subjects_[idx].error = result.status();
      return complete_with(idx, nullptr);
    }
    ++summary_.computed;
    return complete_with(idx, std::make_shared<const FeatureValues>(std::move(result).value()));
  }

  // A subject ready with `values` (null: with its error), then the candidates waiting for it.
  Status complete_with(size_t idx, std::shared_ptr<const FeatureValues> values) {
    Subject& s = subjects_[idx];
    s.ready = true;
    if (values) set_values(s, std::move(values));
    for (size_t c : s.dependents) SOIQ_RETURN_IF_ERROR(evaluate(c));
    return ok_status();
  }

  // A candidate once it and its twin are ready: its row, the predicates, then out or in the sort.
  Status evaluate(size_t i) {
    const Subject& s = subjects_[own_[i]];
    if (evaluated_[i] || !s.ready || (twin_[i] && !subjects_[*twin_[i]].ready)) return ok_status();
    evaluated_[i] = true;
    ++done_;
    if (!s.error.ok()) {
      ++summary_.failed;
      if (summary_.failures.size() < 10)
        summary_.failures.push_back("structure " + std::to_string(s.structure.id) + ": " + s.error.to_string());
      skips_.add(s.error, s.structure.study_uid, s.structure.id);
      return ok_status();
    }
    // Only the scalars the predicates and the order read; the row itself is built when it is
    // sent, so an ordered query with a limit copies records and values for its limit rows alone.
    for (const QueryPredicate& p : q_.where) {
      const std::optional<double> v = scalar_for(p.feature, i);
      if (!v || !compare(*v, p.op, p.value)) return ok_status();
    }
    ++summary_.matched;
    if (q_.order_by) {
      const std::optional<double> key = scalar_for(*q_.order_by, i);
      ordered_.emplace_back(key ? *key : std::nan(""), i);
      return ok_status();
    }
    return send(i);
  }

  // Candidate i's row: its records and every asked value it has.
  QueryRow row_of(size_t i) const {
    QueryRow row;
    for (size_t f = 0; f < q_.features.size(); ++f) {
      RowValue& out = row.values.emplace_back(RowValue{q_.features[f].label, {}});
      if (std::optional<std::vector<double>> v = value_for(f, i)) out.values = std::move(*v);
    }
    row.structure = subjects_[own_[i]].structure;
    row.patient = candidates_[i].patient;
    row.study = candidates_[i].study;
    return row;
  }

  Status send(size_t candidate) {
    if (summary_.returned >= q_.limit) {
      enough_ = true;
      return ok_status();
    }
    ++summary_.returned;
    SOIQ_RETURN_IF_ERROR(out_.row(row_of(candidate)));
    if (summary_.returned >= q_.limit) enough_ = true;
    return ok_status();
  }

  // Query feature f of candidate i (query_subjects.h), or nothing when it cannot be had.
  std::optional<std::vector<double>> value_for(size_t f, size_t i) const {
    return candidate_value(f, q_.features[f].asymmetry, subjects_[own_[i]], twin_subject(i));
  }
  std::optional<double> scalar_for(size_t f, size_t i) const {
    return candidate_scalar(f, q_.features[f].asymmetry, subjects_[own_[i]], twin_subject(i));
  }
  const Subject* twin_subject(size_t i) const { return twin_[i] ? &subjects_[*twin_[i]] : nullptr; }

  // With an order: the matches sorted, missing values (NaN) last in either direction, up to limit.
  Status stream_ordered() {
    if (!q_.order_by) return ok_status();
    std::stable_sort(ordered_.begin(), ordered_.end(), [&](const auto& a, const auto& b) {
      if (std::isnan(a.first) || std::isnan(b.first)) return !std::isnan(a.first) && std::isnan(b.first);
      return q_.descending ? a.first > b.first : a.first < b.first;
    });
    for (auto& entry : ordered_) {
      if (enough_) break;
      SOIQ_RETURN_IF_ERROR(send(entry.second));
    }
    return ok_status();
  }

  const Query& q_;
  db::Store& store_;
  FeatureEngine& features_;
  WorkerPool& pool_;
  SharedStage2* sharing_;  // null: this replica computes alone
  ImageRefsCheck& image_refs_;
  const std::function<Status()>& stop_;
  const QueryOutput& out_;

  std::vector<db::Candidate> candidates_;
  std::vector<Subject> subjects_;
  std::map<int64_t, size_t> subject_of_;     // structure id -> subject
  std::vector<size_t> own_;                  // candidate -> its subject
  std::vector<std::optional<size_t>> twin_;  // candidate -> its twin's subject
  std::map<std::string, std::vector<db::SeriesRecord>> series_of_;
  std::vector<bool> evaluated_;
  std::vector<std::pair<double, size_t>> ordered_;  // order key, candidate
  int64_t done_ = 0;
  bool enough_ = false;  // limit rows sent: nothing more to compute
  QuerySummary summary_;
  QuerySkips skips_;
};

}  // namespace

Result<QuerySummary> QueryEngine::run(const Query& query, const std::function<Status()>& stop, const QueryOutput& out) {
  if (query.limit < 1) return invalid_argument("a query's limit must be >= 1, got " + std::to_string(query.limit));
  return QueryRun(query, store_, features_, pool_, sharing_, image_refs_, stop, out).run(limits_.stage1_cap);
}

}  // namespace soiq::server
