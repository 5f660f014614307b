#include "bench/query_precompute.h"

#include <chrono>
#include <filesystem>
#include <thread>

#include "bench/clock.h"
#include "tests/support/soiqd_process.h"

namespace soiq::bench {
namespace {

namespace fs = std::filesystem;

}  // namespace

v1::QueryRequest precomputed_set_request() {
  v1::QueryRequest r = stage1_only_request();
  r.add_select()->set_name("voxel_volume_mm3");
  r.add_select()->set_name("sphericity");
  v1::FeatureRef* mean = r.add_select();
  mean->set_name("mean");
  mean->set_image("MR");
  r.mutable_order_by()->set_name("voxel_volume_mm3");
  r.set_descending(true);
  r.set_limit(20);
  return r;
}

Result<PrecomputeFigures> precompute_run(const std::string& soiqd, int workers, const std::string& pristine,
                                         const std::string& db, double background_volume_mm3, int runs) {
  fs::copy_file(pristine, db, fs::copy_options::overwrite_existing);
  const Clock::time_point start = Clock::now();
  testing::SoiqdProcess server(db, {"--workers", std::to_string(workers), "--precompute", "on"}, soiqd);
  if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(server.address()));
  PrecomputeFigures f;
  for (bool first = true;; first = false) {
    SOIQ_ASSIGN_OR_RETURN(const v1::ServerInfo info, c.server_info());
    // Every structure of the loaded database is queued (it was stored with precompute off); the
    // worker started before this first look.
    if (first) f.queued = f.structures = info.structures();
    if (info.precompute_failed() > 0)
      return internal_error(std::to_string(info.precompute_failed()) + " structures failed to precompute");
    if (info.precompute_queued() == 0) break;
    // Not more often: `soiq info` counts rows, and a busy poller would take the CPU the worker,
    // at nice 19, is meant to leave to others.
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  f.drain_s = seconds_since(start);
  SOIQ_ASSIGN_OR_RETURN(f.benchmark_after, timed_query(c, benchmark_request()));
  for (int i = 0; i < runs; ++i) {
    SOIQ_ASSIGN_OR_RETURN(TimedQuery t, timed_query(c, benchmark_request()));
    if (t.summary.computed() != 0)
      return internal_error("the benchmark query after precompute computed " + std::to_string(t.summary.computed()) +
                            " structures");
    f.benchmark_again.push_back(std::move(t));
  }
  for (int i = 0; i < runs; ++i) {
    SOIQ_ASSIGN_OR_RETURN(TimedQuery t, timed_query(c, precomputed_set_request()));
    if (t.summary.computed() != 0)
      return internal_error("the precomputed set computed " + std::to_string(t.summary.computed()) + " structures");
    f.precomputed_set.push_back(std::move(t));
  }
  f.threshold_mm3 = background_volume_mm3;
  v1::QueryRequest filter;
  v1::Predicate* p = filter.add_where();
  p->mutable_feature()->set_name("voxel_volume_mm3");
  p->set_op(v1::GT);
  p->set_value(background_volume_mm3);
  for (int i = 0; i < runs; ++i) {
    SOIQ_ASSIGN_OR_RETURN(TimedQuery t, timed_query(c, filter));
    if (t.summary.computed() != 0 || t.summary.stage1_candidates() != t.summary.matched())
      return internal_error("the content filter kept " + std::to_string(t.summary.stage1_candidates()) +
                            " in stage 1 and matched " + std::to_string(t.summary.matched()) + ", computing " +
                            std::to_string(t.summary.computed()));
    f.content_filter.push_back(std::move(t));
  }
  return f;
}

Result<IngestFigures> ingest_with_precompute(const std::string& soiqd, int workers, const std::string& db,
                                             const std::string& work_dir, const std::vector<CohortPatient>& cohort,
                                             const QueryCohortSize& size) {
  std::error_code ec;
  fs::remove(db, ec);
  testing::SoiqdProcess server(db, {"--workers", std::to_string(workers), "--precompute", "on"}, soiqd);
  if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
  IngestFigures f;
  const Clock::time_point start = Clock::now();
  SOIQ_ASSIGN_OR_RETURN(f.uploaded, upload_matched(server.address(), work_dir, cohort, size, 2));
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(server.address()));
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(const v1::ServerInfo info, c.server_info());
    if (info.precompute_queued() == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  f.until_precomputed_s = seconds_since(start);
  return f;
}

}  // namespace soiq::bench
