#include "server/app/query_cached_values.h"

#include <algorithm>

namespace soiq::server::query_run {
namespace {

// The keys of `subjects` and the entries their plans want, each once.
Result<std::vector<db::CachedFeature>> read(db::FeatureStore& store, const std::vector<const Subject*>& subjects) {
  std::vector<std::string> keys, entries;
  for (const Subject* s : subjects) {
    keys.push_back(s->plan->cache_key);
    for (const WantedValue& w : s->plan->wants) entries.push_back(w.entry);
  }
  for (auto* list : {&keys, &entries}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  if (keys.empty()) return std::vector<db::CachedFeature>{};
  return store.cached_features(keys, entries);
}

void add(std::vector<db::CachedFeature>&& found, CachedValues& out) {
  for (auto& e : found) {
    std::shared_ptr<FeatureValues>& values = out.by_key[e.key];
    if (!values) values = std::make_shared<FeatureValues>();
    (*values)[e.entry] = std::move(e.value);
  }
}

}  // namespace

Result<CachedValues> read_cached_values(db::FeatureStore& store, const std::vector<Subject>& subjects,
                                        const std::vector<size_t>& planned) {
  CachedValues out;
  std::vector<const Subject*> all;
  for (size_t i : planned) all.push_back(&subjects[i]);
  Result<std::vector<db::CachedFeature>> found = read(store, all);
  if (found.ok()) {
    add(std::move(found).value(), out);
    return out;
  }
  if (found.status().code() != StatusCode::kDataLoss) return found.status();
  for (size_t i : planned) {
    Result<std::vector<db::CachedFeature>> one = read(store, {&subjects[i]});
    if (one.ok()) {
      add(std::move(one).value(), out);
    } else if (one.status().code() == StatusCode::kDataLoss) {
      out.damaged.emplace_back(
          i, data_loss("structure " + std::to_string(subjects[i].structure.id) + ": " + one.status().message()));
    } else {
      return one.status();
    }
  }
  return out;
}

}  // namespace soiq::server::query_run
