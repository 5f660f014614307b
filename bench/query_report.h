#pragma once
// The Markdown section `soiq-bench query` prints for BENCHMARKS.md from what it measured.

#include <cstdint>
#include <vector>

#include "bench/cold_breakdown.h"
#include "bench/conversions_alone.h"
#include "bench/query_cohort.h"
#include "bench/query_load.h"
#include "bench/query_precompute.h"
#include "bench/query_runs.h"

namespace soiq::bench {

struct QueryBenchFigures {
  QueryCohortSize size;
  int workers = 0;
  double seconds = 0;  // per client count
  int64_t min_triangles = 0, max_triangles = 0;
  size_t candidates = 0;  // structures stage 1 keeps
  double db_mib = 0;
  LoadFigures background, uploaded;
  std::vector<double> stage1_ms;  // in-process, warm runs
  std::vector<ServerRun> runs;
  std::vector<Throughput> load;
  ColdBreakdown breakdown;
  ConversionsAlone alone;  // the same surfaces converted alone on the workers' thread count
  PrecomputeFigures precompute;
  IngestFigures ingest_precompute_on;
};

void print_query_report(const QueryBenchFigures& f);

}  // namespace soiq::bench
