#pragma once
// The precompute part of `soiq-bench query` (query_bench.h): a soiqd with --precompute on, on a copy
// of the loaded database, whose queue holds every structure (the upload queued them): how fast the
// queue drains, the benchmark query after it, the query of precomputed values only, and a content
// filter over the whole database with no stage-1 filter (stage 1 answers it by index).

#include <cstdint>
#include <string>
#include <vector>

#include "bench/query_cohort.h"
#include "bench/query_load.h"
#include "bench/query_runs.h"
#include "core/base/status.h"

namespace soiq::bench {

struct PrecomputeFigures {
  int64_t queued = 0;                       // structures in the queue at start
  double drain_s = 0;                       // until the queue was empty
  int64_t structures = 0;                   // in the database
  TimedQuery benchmark_after;               // the benchmark query, the first after precompute
  std::vector<TimedQuery> benchmark_again;  // the same query repeated, as the stored-values query is
  std::vector<TimedQuery> precomputed_set;  // volume, sphericity, mean inside: every value stored
  double threshold_mm3 = 0;                 // of the content filter
  std::vector<TimedQuery> content_filter;   // voxel_volume_mm3 > threshold, no stage-1 filter
};

// Ingest with precompute on: the matched patients uploaded (2 clients) to a fresh soiqd on an empty
// database, then the time until every structure is precomputed (the uploads' own figures beside
// load()'s, which ran with precompute off).
struct IngestFigures {
  LoadFigures uploaded;
  double until_precomputed_s = 0;  // from the first upload to an empty queue
};
Result<IngestFigures> ingest_with_precompute(const std::string& soiqd, int workers, const std::string& db,
                                             const std::string& work_dir, const std::vector<CohortPatient>& cohort,
                                             const QueryCohortSize& size);

// `background_volume_mm3`: the largest voxel volume of a background surface on the default grid;
// the content filter keeps the structures above it (matched ones only), so what it keeps is known.
Result<PrecomputeFigures> precompute_run(const std::string& soiqd, int workers, const std::string& pristine,
                                         const std::string& db, double background_volume_mm3, int runs);

// The benchmark's stage-1 filter with volume, sphericity and mean inside the MR image: every value
// precompute stores.
v1::QueryRequest precomputed_set_request();

}  // namespace soiq::bench
