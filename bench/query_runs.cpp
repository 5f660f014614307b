#include "bench/query_runs.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "bench/clock.h"
#include "bench/query_cohort.h"
#include "tests/support/soiqd_process.h"

namespace soiq::bench {
namespace {

namespace fs = std::filesystem;

v1::Stage1Filter to_proto(const db::Stage1Filter& f) {
  v1::Stage1Filter out;
  out.set_sex(f.sex);
  out.set_modality(f.modality);
  out.set_study_date_from(f.study_date_from);
  out.set_study_date_to(f.study_date_to);
  out.set_min_age_years(*f.min_age_years);
  out.set_max_age_years(*f.max_age_years);
  return out;
}

}  // namespace

v1::QueryRequest stage1_only_request() {
  v1::QueryRequest r;
  *r.mutable_stage1() = to_proto(query_stage1_filter());
  return r;
}

v1::QueryRequest benchmark_request() {
  v1::QueryRequest r = stage1_only_request();
  r.add_select()->set_name("voxel_volume_mm3");
  r.add_select()->set_name("sphericity");
  v1::FeatureRef* mean = r.add_select();
  mean->set_name("mean");
  mean->set_region("shell:3");
  mean->set_image("MR");
  r.mutable_order_by()->set_name("voxel_volume_mm3");
  r.set_descending(true);
  r.set_limit(20);
  return r;
}

Result<TimedQuery> timed_query(const client::Client& c, const v1::QueryRequest& r) {
  TimedQuery t;
  client::QueryHandlers h;
  h.on_row = [&](const v1::QueryRow& row) {
    ++t.rows;
    if (row.values_size() > 0) t.kept.push_back(row);
    return true;
  };
  const Clock::time_point t0 = Clock::now();
  SOIQ_ASSIGN_OR_RETURN(t.summary, c.query(r, h));
  t.client_ms = ms_since(t0);
  if (t.summary.failed() > 0)
    return internal_error("the query failed on " + std::to_string(t.summary.failed()) +
                          " structures: " + (t.summary.failures_size() ? t.summary.failures(0) : ""));
  return t;
}

Stats stats(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  if (v.empty()) return {};
  return {v.front(), v[v.size() / 2], v[std::min(v.size() - 1, size_t(double(v.size()) * 0.95))]};
}

Result<client::Client> connect(const std::string& address) {
  client::ClientOptions o;
  o.address = address;
  return client::Client::connect(o);
}

Result<ServerRun> server_run(const std::string& soiqd, int workers, const std::string& pristine, const std::string& db,
                             int warm_runs) {
  fs::copy_file(pristine, db, fs::copy_options::overwrite_existing);
  testing::SoiqdProcess server(db, {"--workers", std::to_string(workers)}, soiqd);
  if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(server.address()));
  SOIQ_RETURN_IF_ERROR(c.server_info().status());
  ServerRun run;
  SOIQ_ASSIGN_OR_RETURN(run.stage1, timed_query(c, stage1_only_request()));
  SOIQ_ASSIGN_OR_RETURN(run.stage1_again, timed_query(c, stage1_only_request()));
  SOIQ_ASSIGN_OR_RETURN(run.cold, timed_query(c, benchmark_request()));
  for (int i = 0; i < warm_runs; ++i) {
    SOIQ_ASSIGN_OR_RETURN(TimedQuery w, timed_query(c, benchmark_request()));
    run.warm.push_back(w);
  }
  return run;
}

Result<Throughput> throughput(const std::vector<std::string>& addresses, int clients, double seconds) {
  std::vector<std::vector<double>> latencies(static_cast<size_t>(clients));
  std::vector<Status> errors(static_cast<size_t>(clients), ok_status());
  std::vector<std::thread> threads;
  const Clock::time_point t0 = Clock::now();
  const Clock::time_point until = t0 + std::chrono::milliseconds(int64_t(seconds * 1000));
  for (int i = 0; i < clients; ++i) {
    threads.emplace_back([&, i] {
      Result<client::Client> c = connect(addresses[size_t(i) % addresses.size()]);
      if (!c.ok()) {
        errors[size_t(i)] = c.status();
        return;
      }
      const v1::QueryRequest r = benchmark_request();
      while (Clock::now() < until) {
        Result<TimedQuery> t = timed_query(*c, r);
        if (!t.ok()) {
          errors[size_t(i)] = t.status();
          return;
        }
        latencies[size_t(i)].push_back(t->client_ms);
      }
    });
  }
  for (std::thread& t : threads) t.join();
  const double wall_s = ms_since(t0) / 1000;
  for (const Status& s : errors) SOIQ_RETURN_IF_ERROR(s);
  std::vector<double> all;
  for (const auto& l : latencies) all.insert(all.end(), l.begin(), l.end());
  Throughput out;
  out.clients = clients;
  out.queries = int64_t(all.size());
  out.per_second = double(all.size()) / wall_s;
  out.latency = stats(all);
  return out;
}

}  // namespace soiq::bench
