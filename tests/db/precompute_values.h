#pragma once
// What the precompute tests (store_precompute_test.cpp on every backend, and the SQLite plan test
// in sqlite_store_precompute_test.cpp) write and read: a structure's stored values as the
// precompute worker finds them, the queue, and what a stored-feature condition keeps.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "db/store.h"

namespace soiq::db::testing {

inline std::vector<int64_t> queued_ids(Store& store) {
  auto q = store.precompute_queue(1000);
  EXPECT_TRUE(q.ok()) << q.status().to_string();
  std::vector<int64_t> ids;
  if (q.ok())
    for (const StructureRecord& s : *q) ids.push_back(s.id);
  return ids;
}

inline Precomputed values_for(const StructureRecord& s, double volume) {
  Precomputed p;
  p.structure_id = s.id;
  p.surface_sha256 = s.surface.sha256;
  p.definitions_version = 7;
  p.values.assign(stored_feature_names().size(), std::optional<double>(0.5));
  p.values[0] = volume;  // voxel_volume_mm3
  p.cache_entries = {{"v7|" + s.surface.sha256 + "|grid|nonzero|", "voxel_volume_mm3", {volume}}};
  return p;
}

// The ids stage 1 keeps with voxel_volume_mm3 > 100.
inline std::vector<int64_t> large(Store& store) {
  Stage1Filter f;
  f.stored_features.push_back({"voxel_volume_mm3", Comparison::kGreater, 100});
  auto got = store.stage1(f, 1000);
  EXPECT_TRUE(got.ok()) << got.status().to_string();
  std::vector<int64_t> ids;
  if (got.ok())
    for (const Candidate& c : *got) ids.push_back(c.structure.id);
  return ids;
}

}  // namespace soiq::db::testing
