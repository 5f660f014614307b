#pragma once
// The timed pieces of `soiq-bench query` (query_bench.h): the benchmark's requests, one query timed
// through the real client, a run of a fresh soiqd (stage 1 alone, cold, warm), and concurrent
// clients repeating the warm query. Each fails on any structure the server could not compute.

#include <cstdint>
#include <string>
#include <vector>

#include "client/soiq_client.h"
#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::bench {

// The stage-1 filter of query_cohort.h alone, as a request with no feature.
v1::QueryRequest stage1_only_request();
// Voxel volume and sphericity of each structure, mean MR intensity in a 3 mm shell, by volume, top 20.
v1::QueryRequest benchmark_request();

struct Stats {
  double best = 0, median = 0, p95 = 0;
};
Stats stats(std::vector<double> v);

struct TimedQuery {
  v1::QuerySummary summary;
  double client_ms = 0;
  int64_t rows = 0;
  std::vector<v1::QueryRow> kept;  // the rows of a query with features (top 20)
};
Result<TimedQuery> timed_query(const client::Client& c, const v1::QueryRequest& r);

Result<client::Client> connect(const std::string& address);

struct ServerRun {
  TimedQuery stage1, stage1_again, cold;  // stage 1 first on the fresh server, then once more
  std::vector<TimedQuery> warm;
};
// A fresh soiqd (`soiqd`, --workers `workers`) on a fresh copy `db` of the loaded database
// `pristine`: stage 1 alone, cold, then `warm_runs` warm queries.
Result<ServerRun> server_run(const std::string& soiqd, int workers, const std::string& pristine, const std::string& db,
                             int warm_runs);

struct Throughput {
  int clients = 0;
  int64_t queries = 0;
  double per_second = 0;
  Stats latency;
};
// `clients` threads, each with its own channel (client i to addresses[i % n]: replicas in round
// robin), repeat the warm query for `seconds`.
Result<Throughput> throughput(const std::vector<std::string>& addresses, int clients, double seconds);

}  // namespace soiq::bench
