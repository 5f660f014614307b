#include "bench/query_bench.h"

#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include "bench/clock.h"
#include "bench/cold_breakdown.h"
#include "bench/query_cohort.h"
#include "bench/query_load.h"
#include "bench/query_precompute.h"
#include "bench/query_report.h"
#include "bench/query_runs.h"
#include "client/soiq_client.h"
#include "core/geometry/mesh_defects.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/voxelize_1d.h"
#include "db/sqlite/sqlite_store.h"
#include "server/util/malloc_tuning.h"
#include "tests/support/soiqd_process.h"

namespace soiq::bench {
namespace {

namespace fs = std::filesystem;

void note(const char* fmt, const std::string& s = "") { std::fprintf(stderr, fmt, s.c_str()); }

struct QueryBenchOptions {
  QueryCohortSize size;
  std::string dir, soiqd = SOIQD_BINARY;
  int workers = 2, runs = 3;
  double seconds = 3;
  bool small = false;
};

Result<QueryBenchOptions> parse(const CliArgs& args) {
  QueryBenchOptions o;
  o.small = args.has("--small");
  if (o.small) {
    o.size.patients = 10000;
    o.size.matched = 10;
    o.size.max_triangles = 20000;
    o.seconds = 1;
  }
  SOIQ_ASSIGN_OR_RETURN(o.size.patients, args.get_int("--patients", o.size.patients));
  SOIQ_ASSIGN_OR_RETURN(o.size.matched, args.get_int("--matched", o.size.matched));
  SOIQ_ASSIGN_OR_RETURN(o.workers, args.get_int("--workers", o.workers));
  SOIQ_ASSIGN_OR_RETURN(o.runs, args.get_int("--runs", o.runs));
  SOIQ_ASSIGN_OR_RETURN(o.seconds, args.get_double("--seconds", o.seconds));
  o.dir = args.get("--dir", "");
  o.soiqd = args.get("--soiqd", o.soiqd);
  if (o.size.patients < 1 || o.size.matched < 1 || o.size.matched > o.size.patients)
    return invalid_argument("--patients and --matched must be >= 1, with matched <= patients");
  if (o.workers < 1 || o.runs < 1 || o.seconds <= 0)
    return invalid_argument("--workers and --runs must be >= 1, --seconds > 0");
  return o;
}

// A work folder removed at the end unless the user gave it.
class WorkDir {
 public:
  explicit WorkDir(const std::string& given) : keep_(!given.empty()) {
    if (keep_) {
      path_ = given;
      fs::create_directories(path_);
      return;
    }
    // $SOIQ_BENCH_TMP, else $TMPDIR, else the system's temporary folder: the database needs ~1 GiB.
    const char* base = std::getenv("SOIQ_BENCH_TMP");
    if (!base || !*base) base = std::getenv("TMPDIR");
    std::string pattern = ((base && *base) ? fs::path(base) : fs::temp_directory_path()) / "soiq-bench-query-XXXXXX";
    if (mkdtemp(pattern.data())) path_ = pattern;
  }
  ~WorkDir() {
    std::error_code ec;
    if (!keep_ && !path_.empty()) fs::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  bool keep_;
  std::string path_;
};

Status check_meshes(const CohortPatient& p, const QueryCohortSize& size, int64_t& min_t, int64_t& max_t) {
  for (const cohort::SyntheticStructure& s : matched_structures(p, size)) {
    const MeshDefects d = mesh_defects(s.surface);
    if (!d.closed() || d.degenerate_triangles || d.nonmanifold_edges || signed_volume_mm3(s.surface) <= 0)
      return internal_error("cohort mesh " + s.name + "_" + s.laterality + " has defects: " + describe(d));
    min_t = std::min(min_t, int64_t(s.surface.triangles.size()));
    max_t = std::max(max_t, int64_t(s.surface.triangles.size()));
  }
  return ok_status();
}

// The cohort's patients, every matched structure's mesh checked closed, and their triangle range.
Result<std::vector<CohortPatient>> checked_cohort(const QueryBenchOptions& o, QueryBenchFigures& f) {
  note("soiq-bench query: cohort of %s patients\n", std::to_string(o.size.patients));
  std::vector<CohortPatient> cohort = query_cohort_patients(o.size, 20250409);
  f.min_triangles = INT64_MAX;
  for (const CohortPatient& p : cohort)
    if (p.matched) SOIQ_RETURN_IF_ERROR(check_meshes(p, o.size, f.min_triangles, f.max_triangles));
  return cohort;
}

// Background rows through SqliteStore, then the matched patients uploaded through a real soiqd.
Status load(const QueryBenchOptions& o, const std::vector<CohortPatient>& cohort, const WorkDir& work,
            const std::string& pristine, QueryBenchFigures& f) {
  note("soiq-bench query: bulk load through SqliteStore\n");
  SOIQ_ASSIGN_OR_RETURN(f.background, load_background(pristine, cohort, o.size));

  note("soiq-bench query: uploads through soiqd\n");
  testing::SoiqdProcess server(pristine, {"--workers", std::to_string(o.workers)}, o.soiqd);
  if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
  SOIQ_ASSIGN_OR_RETURN(f.uploaded, upload_matched(server.address(), work.path(), cohort, o.size, 2));
  if (server.terminate() != 0) return internal_error("soiqd did not stop cleanly: " + server.log());
  f.db_mib = double(fs::file_size(pristine)) / (1 << 20);
  return ok_status();
}

// SqliteStore::stage1 in-process, 20 warm runs; each must keep exactly the matched patients.
Status stage1_in_process(const QueryBenchOptions& o, const std::string& pristine, QueryBenchFigures& f) {
  note("soiq-bench query: stage 1 in-process\n");
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqliteStore> store, db::SqliteStore::open(pristine, {}));
  for (int i = 0; i < 21; ++i) {
    const Clock::time_point t0 = Clock::now();
    SOIQ_ASSIGN_OR_RETURN(const std::vector<db::Candidate> c, store->stage1(query_stage1_filter(), 100000));
    if (i > 0) f.stage1_ms.push_back(ms_since(t0));  // the first run warms the page cache
    std::set<std::string> patients;
    for (const db::Candidate& x : c) patients.insert(x.patient.patient_id);
    if (patients.size() != size_t(o.size.matched) || c.size() != size_t(10 * o.size.matched))
      return internal_error("stage 1 keeps " + std::to_string(patients.size()) + " patients and " +
                            std::to_string(c.size()) + " structures, expected " + std::to_string(o.size.matched) +
                            " and " + std::to_string(10 * o.size.matched));
    f.candidates = c.size();
  }
  return ok_status();
}

// --runs fresh servers (cold, then warm), then concurrent clients on the warm database of the last.
Status server_runs(const QueryBenchOptions& o, const WorkDir& work, const std::string& pristine, QueryBenchFigures& f) {
  for (int i = 0; i < o.runs; ++i) {
    note("soiq-bench query: cold and warm, run %s\n", std::to_string(i + 1));
    SOIQ_ASSIGN_OR_RETURN(ServerRun r, server_run(o.soiqd, o.workers, pristine, work.path() + "/run.db", 5));
    if (r.cold.summary.computed() != int64_t(f.candidates) ||
        r.warm.back().summary.cache_hits() != int64_t(f.candidates))
      return internal_error("cold computed " + std::to_string(r.cold.summary.computed()) + ", warm hit " +
                            std::to_string(r.warm.back().summary.cache_hits()) + " of " + std::to_string(f.candidates));
    f.runs.push_back(std::move(r));
  }
  note("soiq-bench query: concurrent clients\n");
  testing::SoiqdProcess server(work.path() + "/run.db", {"--workers", std::to_string(o.workers)}, o.soiqd);
  if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(server.address()));
  SOIQ_RETURN_IF_ERROR(timed_query(c, benchmark_request()).status());  // warms the page cache
  for (int clients : {1, 2, 4, 8}) {
    SOIQ_ASSIGN_OR_RETURN(Throughput t, throughput({server.address()}, clients, o.seconds));
    f.load.push_back(t);
  }
  return ok_status();
}

// Where the cold time goes, in-process; the server's rows must hold exactly the values computed here.
Status breakdown(const WorkDir& work, const std::string& pristine, QueryBenchFigures& f) {
  note("soiq-bench query: where the cold time goes (in-process, one thread)\n");
  fs::copy_file(pristine, work.path() + "/breakdown.db", fs::copy_options::overwrite_existing);
  SOIQ_ASSIGN_OR_RETURN(f.breakdown, cold_breakdown(work.path() + "/breakdown.db", query_stage1_filter()));
  note("soiq-bench query: the same surfaces converted alone\n");
  SOIQ_ASSIGN_OR_RETURN(f.alone, conversions_alone(pristine, query_stage1_filter(), f.workers));
  for (const ServerRun& r : f.runs) {
    for (const TimedQuery* t : {&r.cold, &r.warm.back()}) {
      if (t->kept.size() != size_t(std::min<int64_t>(20, int64_t(f.candidates))))
        return internal_error("the query returned " + std::to_string(t->kept.size()) + " rows");
      for (const v1::QueryRow& row : t->kept) {
        auto it = f.breakdown.values.find(row.structure().id());
        for (int i = 0; i < 3; ++i) {
          if (it == f.breakdown.values.end() || row.values(i).value_size() != 1 ||
              row.values(i).value(0) != it->second[size_t(i)])
            return internal_error("structure " + std::to_string(row.structure().id()) + ": the server's " +
                                  row.values(i).name() + " differs from the in-process value");
        }
      }
    }
  }
  return ok_status();
}

// The largest voxel volume of a background surface on the default grid (1 mm): the content filter's
// threshold, so that it keeps matched structures only.
Result<double> largest_background_volume(const QueryCohortSize& size) {
  double largest = 0;
  for (int b = 0; b < std::max(1, size.background_blobs); ++b) {
    const TriangleMesh mesh = background_surface(b);
    SOIQ_ASSIGN_OR_RETURN(const ImageGeometry g, grid_around(mesh, {1, 1, 1}, 2));
    SOIQ_ASSIGN_OR_RETURN(const Voxelization v, voxelize_1d(mesh, g));
    largest = std::max(largest, double(voxel_count(v.volume)));
  }
  return largest;
}

// With precompute on, on a copy of the loaded database (every structure queued); then the matched
// patients' uploads again, to a fresh soiqd with precompute on.
Status precompute(const QueryBenchOptions& o, const std::vector<CohortPatient>& cohort, const WorkDir& work,
                  const std::string& pristine, QueryBenchFigures& f) {
  note("soiq-bench query: precompute, then queries on stored values\n");
  SOIQ_ASSIGN_OR_RETURN(const double threshold, largest_background_volume(o.size));
  SOIQ_ASSIGN_OR_RETURN(f.precompute,
                        precompute_run(o.soiqd, o.workers, pristine, work.path() + "/pre.db", threshold, 10));
  note("soiq-bench query: uploads with precompute on\n");
  SOIQ_ASSIGN_OR_RETURN(f.ingest_precompute_on, ingest_with_precompute(o.soiqd, o.workers, work.path() + "/ingest.db",
                                                                       work.path(), cohort, o.size));
  return ok_status();
}

Status run(const QueryBenchOptions& o) {
  const WorkDir work(o.dir);
  if (work.path().empty()) return internal_error("cannot create a work folder (set SOIQ_BENCH_TMP or --dir)");
  const std::string pristine = work.path() + "/cohort.db";
  QueryBenchFigures f;
  f.size = o.size;
  f.workers = o.workers;
  f.seconds = o.seconds;
  SOIQ_ASSIGN_OR_RETURN(const std::vector<CohortPatient> cohort, checked_cohort(o, f));
  SOIQ_RETURN_IF_ERROR(load(o, cohort, work, pristine, f));
  SOIQ_RETURN_IF_ERROR(stage1_in_process(o, pristine, f));
  SOIQ_RETURN_IF_ERROR(server_runs(o, work, pristine, f));
  SOIQ_RETURN_IF_ERROR(breakdown(work, pristine, f));
  SOIQ_RETURN_IF_ERROR(precompute(o, cohort, work, pristine, f));
  print_query_report(f);
  return ok_status();
}

}  // namespace

int run_query_bench(const CliArgs& args) {
  // The in-process parts (stage 1, where the cold time goes) allocate as soiqd does.
  server::keep_freed_blocks_for_reuse();
  Result<QueryBenchOptions> o = parse(args);
  if (!o.ok()) {
    std::fprintf(stderr, "soiq-bench query: %s\n", o.status().message().c_str());
    return 2;
  }
  const Status s = run(*o);
  if (!s.ok()) {
    std::fprintf(stderr, "soiq-bench query: %s\n", s.to_string().c_str());
    return 1;
  }
  return 0;
}

}  // namespace soiq::bench
