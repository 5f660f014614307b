#pragma once
// The feature cache and the precompute queue, one of the store's three roles (db/store.h):
// feature values kept per surface and computation context, and the default features soiqd computes
// for every structure when it arrives (docs/DESIGN.md "Queries").
//
// The store's contract (db/store.h) holds for every method here: one transaction per write, errors
// as soiq::Status codes, safe to call from many threads at once.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/store_records.h"

namespace soiq::db {

// Feature cache. A cache key names one computation context: surface sha256, grid, conversion
// options and feature-definition version (built by the server); an entry is one feature value in
// that context, under a name that includes region and image ("mean|shell_3mm|<image sha>").
struct CachedFeature {
  std::string key;
  std::string entry;
  std::vector<double> value;
};

// One surface's feature-cache entries, as a batch write takes them.
struct SurfaceFeatures {
  std::string surface_sha256;
  std::vector<CachedFeature> entries;
};

// Which features precompute computed for a structure (soiqd --precompute on|weighted). Each set
// holds the ones before it, so the stored number orders them: a structure stored with a smaller set
// than soiqd's now is queued again (requeue_precompute), one with a larger set keeps its values.
enum class PrecomputedSet { kDefault = 0, kWithWeighted = 1 };

// What soiqd's precompute worker found for one structure it took from the queue.
struct Precomputed {
  int64_t structure_id = 0;
  std::string surface_sha256;                     // the surface the values belong to
  int definitions_version = 0;                    // feature_definitions_version() they were computed under
  PrecomputedSet set = PrecomputedSet::kDefault;  // what was computed (an image that failed included)
  // By stored_feature_names(); nullopt (or NaN) when the structure has no such value.
  std::vector<std::optional<double>> values;
  std::vector<CachedFeature> cache_entries;  // every value computed, for the feature cache
  // Non-empty when the precompute failed (why, for `soiq info` and the log): the structure leaves
  // the queue without stored values, and queries compute its features themselves.
  std::string failure;
};

// The features' role: 6 methods, each one transaction.
class FeatureStore {
 public:
  virtual ~FeatureStore() = default;

  // Stores feature-cache entries; `surface_sha256` ties them to the surface so they go with it.
  virtual Status put_cached_features(const std::string& surface_sha256, const std::vector<CachedFeature>& entries) = 0;
  // Many surfaces' entries in one transaction (a query writes its results so, not one transaction
  // per structure). A surface deleted meanwhile is skipped: nothing would read its entries.
  virtual Status put_cached_features(const std::vector<SurfaceFeatures>& batch) = 0;
  // Stores what the precompute worker found for each structure (values, cache entries; or the
  // failure) and takes it out of the queue, all in one transaction. A structure that is gone, or
  // whose surface is no longer `surface_sha256` (replaced meanwhile, and queued again), is skipped.
  virtual Status put_precomputed(const std::vector<Precomputed>& batch) = 0;
  // Every structure whose stored values were computed under another definitions version loses
  // them and is queued again; one whose values are of this version but of a smaller set than `set`
  // is queued again keeping them (they are right, only fewer: stage 1 goes on filtering on them).
  // soiqd calls it at start, before serving. Returns how many were queued.
  virtual Result<int64_t> requeue_precompute(int definitions_version, PrecomputedSet set) = 0;

  // The cached entries under each key (one round trip for many keys): those named in `entries`,
  // or every one when it is empty. A query wants a few of the ~75 entries a key holds; the others
  // are not copied out of the database.
  virtual Result<std::vector<CachedFeature>> cached_features(const std::vector<std::string>& keys,
                                                             const std::vector<std::string>& entries) = 0;
  // Up to `limit` structures waiting for precompute, oldest first (a new structure, one replaced
  // with a new surface, a structure of a study that gained an image). Failed ones are not listed.
  virtual Result<std::vector<StructureRecord>> precompute_queue(int64_t limit) = 0;

  // --- conveniences on the methods above -----------------------------------------------------
  Status put_precomputed(const Precomputed& p) { return put_precomputed(std::vector<Precomputed>{p}); }
  Result<std::vector<CachedFeature>> cached_features(const std::vector<std::string>& keys) {
    return cached_features(keys, {});
  }
};

}  // namespace soiq::db
