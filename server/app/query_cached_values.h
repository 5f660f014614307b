#pragma once
// Internal to query_engine.cpp: the feature cache's values for a query's planned subjects
// (query_subjects.h), by cache key, in one round trip: only the entries some plan wants (a key
// holds every value its context ever computed).
//
// A stored value found damaged (DATA_LOSS: its checksum differs, db/cached_value.h) fails only the
// subjects whose key holds it, as a damaged surface fails only its structures: the keys are then
// read one at a time, and each subject whose read fails is listed in `damaged` with the error,
// naming its structure; the others get their values.
// Errors: the store's others. Cost: one read; one per subject after a damaged value.

#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/query_subjects.h"

namespace soiq::server::query_run {

struct CachedValues {
  std::unordered_map<std::string, std::shared_ptr<FeatureValues>> by_key;  // cache key -> its entries
  std::vector<std::pair<size_t, Status>> damaged;                          // subject -> why its values cannot be read
};

Result<CachedValues> read_cached_values(db::FeatureStore& store, const std::vector<Subject>& subjects,
                                        const std::vector<size_t>& planned);

}  // namespace soiq::server::query_run
