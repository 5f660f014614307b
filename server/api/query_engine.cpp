#include "server/api/query_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include "core/features/asymmetry_index.h"
#include "server/api/proto_records.h"
#include "server/api/query_request.h"

namespace soiq::server {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// One structure whose features the query needs: a candidate, or a candidate's twin.
struct Subject {
  db::StructureRecord structure;
  std::optional<FeaturePlan> plan;
  Status error;
  FeatureValues values;
  bool ready = false;
  std::vector<size_t> dependents;  // candidates waiting for this subject
};

// What the workers hand back to the query's thread.
struct Completions {
  std::mutex mutex;
  std::condition_variable wake;
  std::deque<std::pair<size_t, Result<FeatureValues>>> done;
  std::atomic<bool> cancelled{false};
};

// The value a row shows for a reference, or nothing when it cannot be had.
std::optional<std::vector<double>> value_of(const ParsedRef& ref, const FeatureAsk& ask, const Subject& s) {
  if (!s.ready || !s.error.ok() || !s.plan) return std::nullopt;
  std::string entry = ref.name;
  if (ref.intensity) {
    const size_t image = std::find(ask.images.begin(), ask.images.end(), ref.image) - ask.images.begin();
    entry = feature_entry(ref.name, region_name(ref.region), s.plan->images.at(image).sha256, ask.interpolation);
  }
  auto it = s.values.find(entry);
  if (it == s.values.end()) return std::nullopt;
  return it->second;
}

}  // namespace

Status QueryEngine::run(const v1::QueryRequest& request, const std::function<Status()>& stop,
                        const std::function<bool(const v1::QueryEvent&)>& emit) {
  const Clock::time_point start = Clock::now();
  SOIQ_ASSIGN_OR_RETURN(ParsedQuery q, parse_query(request, limits_.result_cap));
  SOIQ_ASSIGN_OR_RETURN(std::vector<db::Candidate> candidates, store_.stage1(q.stage1, limits_.stage1_cap));
  v1::QuerySummary summary;
  summary.set_stage1_candidates(int64_t(candidates.size()));
  summary.set_stage1_ms(ms_since(start));
  const Clock::time_point stage2_start = Clock::now();

  auto send = [&](const v1::QueryEvent& e) -> Status {
    if (!emit(e)) return Status(StatusCode::kCancelled, "the client closed the query stream");
    return ok_status();
  };
  auto progress = [&](const char* stage, int64_t done, int64_t total) {
    v1::QueryEvent e;
    e.mutable_progress()->set_stage(stage);
    e.mutable_progress()->set_done(done);
    e.mutable_progress()->set_total(total);
    return send(e);
  };
  SOIQ_RETURN_IF_ERROR(progress("stage1", int64_t(candidates.size()), int64_t(candidates.size())));

  // Studies' series and structures, read once per study.
  std::map<std::string, std::vector<db::SeriesRecord>> series_of;
  std::map<std::string, std::vector<db::StructureRecord>> structures_of;
  auto study_series = [&](const std::string& uid) -> Result<const std::vector<db::SeriesRecord>*> {
    auto it = series_of.find(uid);
    if (it == series_of.end()) {
      SOIQ_ASSIGN_OR_RETURN(auto list, store_.list_series(uid));
      it = series_of.emplace(uid, std::move(list)).first;
    }
    return &it->second;
  };

  std::vector<Subject> subjects;
  std::map<int64_t, size_t> subject_of;
  auto add_subject = [&](const db::StructureRecord& s, size_t candidate) {
    auto [it, fresh] = subject_of.emplace(s.id, subjects.size());
    if (fresh) subjects.push_back(Subject{s, std::nullopt, ok_status(), {}, false, {}});
    subjects[it->second].dependents.push_back(candidate);
    return it->second;
  };
  std::vector<size_t> own(candidates.size());
  std::vector<std::optional<size_t>> twin(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) own[i] = add_subject(candidates[i].structure, i);
  if (q.needs_twins) {
    for (size_t i = 0; i < candidates.size(); ++i) {
      const db::StructureRecord& s = candidates[i].structure;
      if (s.laterality.empty()) continue;
      auto it = structures_of.find(s.study_uid);
      if (it == structures_of.end()) {
        db::StructureFilter f;
        f.study_uid = s.study_uid;
        std::vector<db::StructureRecord> all;
        db::PageRequest page;
        page.page_size = 1000;
        do {
          SOIQ_ASSIGN_OR_RETURN(auto p, store_.list_structures(f, page));
          all.insert(all.end(), p.items.begin(), p.items.end());
          page.page_token = p.next_page_token;
        } while (!page.page_token.empty());
        it = structures_of.emplace(s.study_uid, std::move(all)).first;
      }
      const std::string other = s.laterality == "L" ? "R" : "L";
      for (const db::StructureRecord& t : it->second) {
        if (t.laterality == other && lower(t.name) == lower(s.name)) {
          twin[i] = add_subject(t, i);
          break;
        }
      }
    }
  }

  // Plans, then the cache for every plan in one round trip.
  const bool features_asked = !q.ask.names.empty();
  std::vector<std::string> keys;
  for (Subject& s : subjects) {
    if (!features_asked) {
      s.ready = true;
      continue;
    }
    Result<const std::vector<db::SeriesRecord>*> series = study_series(s.structure.study_uid);
    if (!series.ok()) return series.status();
    Result<FeaturePlan> plan = features_.plan(s.structure, **series, q.ask);
    if (!plan.ok()) {
      s.error = plan.status();
      s.ready = true;
      continue;
    }
    s.plan = std::move(plan).value();
    keys.push_back(s.plan->cache_key);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::map<std::string, FeatureValues> cached;
  if (!keys.empty()) {
    SOIQ_ASSIGN_OR_RETURN(std::vector<db::CachedFeature> entries, store_.cached_features(keys));
    for (auto& e : entries) cached[e.key][e.entry] = std::move(e.value);
  }
  int64_t cache_hits = 0, computed = 0;
  std::vector<size_t> to_compute;
  for (size_t i = 0; i < subjects.size(); ++i) {
    Subject& s = subjects[i];
    if (s.ready) continue;
    const FeatureValues& have = cached[s.plan->cache_key];
    const bool complete = std::all_of(s.plan->wants.begin(), s.plan->wants.end(),
                                      [&](const WantedValue& w) { return have.count(w.entry) > 0; });
    if (complete) {
      s.values = have;
      s.ready = true;
      ++cache_hits;
    } else {
      to_compute.push_back(i);
    }
  }

  // Evaluation of a candidate once it and its twin are ready.
  int64_t matched = 0, returned = 0, failed = 0, done = 0;
  std::vector<std::string> failures;
  std::vector<std::pair<double, v1::QueryRow>> ordered;
  std::vector<bool> evaluated(candidates.size(), false);
  bool enough = false;
  auto evaluate = [&](size_t i) -> Status {
    if (evaluated[i]) return ok_status();
    const Subject& s = subjects[own[i]];
    if (!s.ready || (twin[i] && !subjects[*twin[i]].ready)) return ok_status();
    evaluated[i] = true;
    ++done;
    if (!s.error.ok()) {
      ++failed;
      if (failures.size() < 10)
        failures.push_back("structure " + std::to_string(s.structure.id) + ": " + s.error.to_string());
      return ok_status();
    }
    v1::QueryRow row;
    std::vector<std::optional<double>> scalar(q.refs.size());
    for (size_t r = 0; r < q.refs.size(); ++r) {
      const ParsedRef& ref = q.refs[r];
      std::optional<std::vector<double>> v = value_of(ref, q.ask, s);
      if (ref.asymmetry) {
        std::optional<std::vector<double>> t;
        if (twin[i]) t = value_of(ref, q.ask, subjects[*twin[i]]);
        if (v && t && v->size() == 1 && t->size() == 1) {
          const bool left = s.structure.laterality == "L";
          Result<double> a = left ? asymmetry_index((*v)[0], (*t)[0]) : asymmetry_index((*t)[0], (*v)[0]);
          v = a.ok() ? std::optional<std::vector<double>>(std::vector<double>{*a}) : std::nullopt;
        } else {
          v.reset();
        }
      }
      v1::FeatureValue* out = row.add_values();
      *out = ref.label;
      if (v) {
        for (double x : *v) out->add_value(x);
        if (v->size() == 1) scalar[r] = (*v)[0];
      }
    }
    for (const ParsedPredicate& p : q.where) {
      if (!scalar[p.ref] || !compare(*scalar[p.ref], p.op, p.value)) return ok_status();
    }
    ++matched;
    *row.mutable_structure() = to_proto(s.structure);
    *row.mutable_patient() = to_proto(candidates[i].patient);
    *row.mutable_study() = to_proto(candidates[i].study);
    if (q.order_ref) {
      const std::optional<double> key = scalar[*q.order_ref];
      ordered.emplace_back(key ? *key : std::nan(""), std::move(row));
      return ok_status();
    }
    if (returned >= q.limit) {
      enough = true;
      return ok_status();
    }
    ++returned;
    v1::QueryEvent e;
    *e.mutable_row() = std::move(row);
    SOIQ_RETURN_IF_ERROR(send(e));
    if (returned >= q.limit) enough = true;
    return ok_status();
  };
  for (size_t i = 0; i < candidates.size() && !enough; ++i) SOIQ_RETURN_IF_ERROR(evaluate(i));

  // Compute the misses on the worker pool; evaluate candidates as their subjects complete.
  auto completions = std::make_shared<Completions>();
  auto ask = std::make_shared<const FeatureAsk>(q.ask);
  size_t pending = 0;
  if (!enough) {
    for (size_t idx : to_compute) {
      auto plan = std::make_shared<const FeaturePlan>(*subjects[idx].plan);
      FeatureEngine* engine = &features_;
      pool_.submit([completions, ask, plan, engine, idx] {
        Result<FeatureValues> r = completions->cancelled.load()
                                      ? Result<FeatureValues>(Status(StatusCode::kCancelled, "cancelled"))
                                      : engine->compute(*plan, *ask, &completions->cancelled);
        std::lock_guard<std::mutex> lock(completions->mutex);
        completions->done.emplace_back(idx, std::move(r));
        completions->wake.notify_one();
      });
      ++pending;
    }
  }
  struct CancelOnExit {
    Completions& c;
    ~CancelOnExit() { c.cancelled = true; }
  } cancel_on_exit{*completions};
  Clock::time_point last_progress = Clock::now();
  const int64_t total = int64_t(candidates.size());
  while (pending > 0 && !enough) {
    std::deque<std::pair<size_t, Result<FeatureValues>>> batch;
    {
      std::unique_lock<std::mutex> lock(completions->mutex);
      completions->wake.wait_for(lock, std::chrono::milliseconds(50), [&] { return !completions->done.empty(); });
      batch.swap(completions->done);
    }
    SOIQ_RETURN_IF_ERROR(stop());
    for (auto& [idx, result] : batch) {
      --pending;
      Subject& s = subjects[idx];
      s.ready = true;
      if (result.ok()) {
        s.values = std::move(result).value();
        ++computed;
      } else {
        s.error = result.status();
      }
      for (size_t c : s.dependents) SOIQ_RETURN_IF_ERROR(evaluate(c));
    }
    if (ms_since(last_progress) >= 100 || pending == 0) {
      SOIQ_RETURN_IF_ERROR(progress("stage2", done, total));
      last_progress = Clock::now();
    }
  }
  if (to_compute.empty() || enough) SOIQ_RETURN_IF_ERROR(progress("stage2", done, total));

  if (q.order_ref) {
    // Missing values (NaN) sort last in either direction.
    std::stable_sort(ordered.begin(), ordered.end(), [&](const auto& a, const auto& b) {
      if (std::isnan(a.first) || std::isnan(b.first)) return !std::isnan(a.first) && std::isnan(b.first);
      return q.descending ? a.first > b.first : a.first < b.first;
    });
    for (auto& [key, row] : ordered) {
      if (returned >= q.limit) break;
      ++returned;
      v1::QueryEvent e;
      *e.mutable_row() = std::move(row);
      SOIQ_RETURN_IF_ERROR(send(e));
    }
  }

  summary.set_computed(computed);
  summary.set_cache_hits(cache_hits);
  summary.set_matched(matched);
  summary.set_returned(returned);
  summary.set_failed(failed);
  for (const std::string& f : failures) summary.add_failures(f);
  summary.set_stage2_ms(ms_since(stage2_start));
  summary.set_total_ms(ms_since(start));
  v1::QueryEvent e;
  *e.mutable_summary() = summary;
  return send(e);
}

}  // namespace soiq::server
