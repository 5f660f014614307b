#pragma once
// soiq-bench query: the two-stage query through a real soiqd and the real
// client, on a synthetic cohort of 100,000 patients of whom stage 1 keeps 100 (1,000 surfaces of
// 10k-100k triangles, query_cohort.h). It prints a markdown section for BENCHMARKS.md:
//   - the load: background patients through db::SqliteStore, matched ones uploaded through gRPC;
//   - stage 1 alone: SqliteStore::stage1 in-process, and a feature-less query through the server;
//   - the query "voxel volume, sphericity and mean MR intensity in a 3 mm shell, ordered by
//     volume, top 20": cold (fresh server on a fresh copy of the database: empty feature cache),
//     best and median of --runs, then warm (same query again);
//   - concurrent clients (1, 2, 4, 8) repeating the warm query: queries/s, p50, p95;
//   - where the cold time goes (cold_breakdown.h).
// Options: --small (10,000 patients, 10 matched, 10k-20k triangles; well under a minute),
// --dir DIR (work folder, default a fresh one under $SOIQ_BENCH_TMP, $TMPDIR or /tmp, removed at
// the end), --soiqd PATH,
// --workers N (soiqd's, default 2), --runs N (cold repeats, default 3), --seconds S (per client
// count, default 3), --patients N, --matched N.
// Exit codes: 0 ok, 2 bad options, 1 any failure (the message says which step).

#include "bench/cli_args.h"

namespace soiq::bench {

int run_query_bench(const CliArgs& args);

}  // namespace soiq::bench
