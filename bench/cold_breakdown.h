#pragma once
// "Where the cold time goes" for `soiq-bench query`: the stage-2 work of the cold query, part by
// part, in this process, on one thread, over the same stage-1 candidates the server computes —
// the same steps FeatureEngine::compute takes (server/app/feature_engine.cpp), each timed alone:
// surface blob read and decode, the 1D conversion, the copy of the mesh into StructureInput, volume
// features, surface features (hull-free: mesh volume + area, all sphericity needs, as the server
// computes them; and, marked "(before)" and left out of the sum, surface_shape with its convex hull
// and the mesh copy, as the server did before: timed on one structure in 10, totals extrapolated),
// the 3 mm shell, the image read and decode
// (once per study, as the server caches images), resampling, intensity features, and the cache
// write (one transaction for all: the server batches what its workers finish between two rounds
// of its query thread).
// `db_path` is written to (cache entries): pass a copy. Errors: the store's and the parts'.

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"

namespace soiq::bench {

struct ColdBreakdown {
  int64_t structures = 0;
  int64_t triangles = 0;
  int64_t voxels = 0;        // inside, summed
  int64_t shell_voxels = 0;  // summed
  double stage1_ms = 0;
  std::vector<std::pair<std::string, double>> parts_ms;  // summed over the structures, in order
  double total_ms = 0;                                   // wall time of the whole pass
  // structure id -> voxel_volume_mm3, sphericity, mean MR intensity in the 3 mm shell
  std::map<int64_t, std::array<double, 3>> values;
};

Result<ColdBreakdown> cold_breakdown(const std::string& db_path, const db::Stage1Filter& filter);

}  // namespace soiq::bench
