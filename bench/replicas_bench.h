#pragma once
// soiq-bench replicas: soiqd on PostgreSQL beside soiqd on SQLite, on the `soiq-bench query`
// cohort (query_cohort.h), in one run on this machine (docs/SCALE_OUT.md). A real PostgreSQL 15
// is started in a temporary folder (tests/support/postgres_process.h). It prints a markdown
// section for BENCHMARKS.md:
//   - ingest: the matched patients' uploads through soiqd, on SQLite and on PostgreSQL;
//   - migration: the whole loaded store copied SQLite -> PostgreSQL and verified (soiq-admin);
//   - stage 1 alone through soiqd on each backend (a feature-less query; best and median of 20);
//   - one soiqd on each backend: the cold benchmark query on a fresh copy of the store, then the
//     warm query repeated by 1 and by 8 clients (PostgreSQL against SQLite, with their targets);
//   - the cold benchmark query (query_runs.h) on 1, 2 and 3 replicas sharing one database, with
//     each replica's share of the structures computed;
//   - 8 clients repeating the warm query against the three replicas (round robin): queries/s,
//     p50 and p95;
//   - stage 1 at scale: a second cohort of --stage1-patients (default 1,000,000; 0 skips it) in
//     SQLite and migrated to PostgreSQL, stage 1 alone through soiqd on each.
// Options: --small (10,000 patients, 10 matched, 20,000 at scale), --patients N, --matched N,
// --stage1-patients N, --workers N (each replica's, default 2), --seconds S (the clients, default
// 3), --soiqd PATH.
// Exit codes: 0 ok, 2 bad options, 1 any failure (the message says which step).

#include "bench/cli_args.h"

namespace soiq::bench {

int run_replicas_bench(const CliArgs& args);

}  // namespace soiq::bench
