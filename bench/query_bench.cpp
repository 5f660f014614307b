#include "bench/query_bench.h"

#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <thread>

#include "bench/cold_breakdown.h"
#include "bench/query_cohort.h"
#include "bench/query_load.h"
#include "bench/soiqd_child.h"
#include "client/soiq_client.h"
#include "core/geometry/mesh_defects.h"
#include "db/sqlite_store.h"

namespace soiq::bench {
namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

void note(const char* fmt, const std::string& s = "") { std::fprintf(stderr, fmt, s.c_str()); }

struct Options {
  QueryCohortSize size;
  std::string dir, soiqd = SOIQD_BINARY;
  int workers = 2, runs = 3;
  double seconds = 3;
  bool small = false;
};

Result<Options> parse(const CliArgs& args) {
  Options o;
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

v1::QueryRequest stage1_only_request() {
  v1::QueryRequest r;
  *r.mutable_stage1() = to_proto(query_stage1_filter());
  return r;
}

// Voxel volume and sphericity of each structure, mean MR intensity in a 3 mm shell, by volume, top 20.
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

struct Timed {
  v1::QuerySummary summary;
  double client_ms = 0;
  int64_t rows = 0;
  std::vector<v1::QueryRow> kept;  // the rows of a query with features (top 20)
};

Result<Timed> timed_query(const client::Client& c, const v1::QueryRequest& r) {
  Timed t;
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

struct Stats {
  double best = 0, median = 0, p95 = 0;
};

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

struct ServerRun {
  Timed stage1, cold;
  std::vector<Timed> warm;
};

// A fresh soiqd on a fresh copy of the loaded database: stage 1 alone, cold, then warm queries.
Result<ServerRun> server_run(const Options& o, const std::string& pristine, const std::string& db, int warm_runs) {
  fs::copy_file(pristine, db, fs::copy_options::overwrite_existing);
  SoiqdChild server(o.soiqd, db, {"--workers", std::to_string(o.workers)});
  if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(server.address()));
  SOIQ_RETURN_IF_ERROR(c.server_info().status());
  ServerRun run;
  SOIQ_ASSIGN_OR_RETURN(run.stage1, timed_query(c, stage1_only_request()));
  SOIQ_ASSIGN_OR_RETURN(run.cold, timed_query(c, benchmark_request()));
  for (int i = 0; i < warm_runs; ++i) {
    SOIQ_ASSIGN_OR_RETURN(Timed w, timed_query(c, benchmark_request()));
    run.warm.push_back(w);
  }
  return run;
}

struct Throughput {
  int clients = 0;
  int64_t queries = 0;
  double per_second = 0;
  Stats latency;
};

// `clients` threads, each with its own channel, repeat the warm query for `seconds`.
Result<Throughput> throughput(const std::string& address, int clients, double seconds) {
  std::vector<std::vector<double>> latencies(static_cast<size_t>(clients));
  std::vector<Status> errors(static_cast<size_t>(clients), ok_status());
  std::vector<std::thread> threads;
  const Clock::time_point t0 = Clock::now();
  const Clock::time_point until = t0 + std::chrono::milliseconds(int64_t(seconds * 1000));
  for (int i = 0; i < clients; ++i) {
    threads.emplace_back([&, i] {
      Result<client::Client> c = connect(address);
      if (!c.ok()) {
        errors[size_t(i)] = c.status();
        return;
      }
      const v1::QueryRequest r = benchmark_request();
      while (Clock::now() < until) {
        Result<Timed> t = timed_query(*c, r);
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
  for (const CohortStructure& s : matched_structures(p, size)) {
    const MeshDefects d = mesh_defects(s.surface);
    if (!d.closed() || d.degenerate_triangles || d.nonmanifold_edges || signed_volume_mm3(s.surface) <= 0)
      return internal_error("cohort mesh " + s.name + "_" + s.laterality + " has defects: " + describe(d));
    min_t = std::min(min_t, int64_t(s.surface.triangles.size()));
    max_t = std::max(max_t, int64_t(s.surface.triangles.size()));
  }
  return ok_status();
}

Status run(const Options& o) {
  const WorkDir work(o.dir);
  if (work.path().empty()) return internal_error("cannot create a work folder (set SOIQ_BENCH_TMP or --dir)");
  const std::string pristine = work.path() + "/cohort.db";

  note("soiq-bench query: cohort of %s patients\n", std::to_string(o.size.patients));
  const std::vector<CohortPatient> cohort = query_cohort_patients(o.size, 20250409);
  int64_t min_t = INT64_MAX, max_t = 0;
  for (const CohortPatient& p : cohort)
    if (p.matched) SOIQ_RETURN_IF_ERROR(check_meshes(p, o.size, min_t, max_t));

  // Background rows on tmpfs (fsync is free there), then moved next to the rest.
  note("soiq-bench query: bulk load through SqliteStore\n");
  std::string shm = "/dev/shm/soiq-bench-query-XXXXXX";
  if (!mkdtemp(shm.data())) shm = work.path() + "/shm";
  fs::create_directories(shm);
  Result<LoadFigures> background = load_background(shm + "/cohort.db", cohort, o.size);
  if (background.ok()) fs::copy_file(shm + "/cohort.db", pristine, fs::copy_options::overwrite_existing);
  fs::remove_all(shm);
  SOIQ_RETURN_IF_ERROR(background.status());

  note("soiq-bench query: uploads through soiqd\n");
  LoadFigures uploaded;
  {
    SoiqdChild server(o.soiqd, pristine, {"--workers", std::to_string(o.workers)});
    if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
    SOIQ_ASSIGN_OR_RETURN(uploaded, upload_matched(server.address(), work.path(), cohort, o.size, 2));
    if (server.stop() != 0) return internal_error("soiqd did not stop cleanly: " + server.log());
  }
  const double db_mib = double(fs::file_size(pristine)) / (1 << 20);

  note("soiq-bench query: stage 1 in-process\n");
  std::vector<double> stage1_ms;
  size_t candidates = 0;
  {
    SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqliteStore> store, db::SqliteStore::open(pristine, {}));
    for (int i = 0; i < 21; ++i) {
      const Clock::time_point t0 = Clock::now();
      SOIQ_ASSIGN_OR_RETURN(const std::vector<db::Candidate> c, store->stage1(query_stage1_filter(), 100000));
      if (i > 0) stage1_ms.push_back(ms_since(t0));  // the first run warms the page cache
      std::set<std::string> patients;
      for (const db::Candidate& x : c) patients.insert(x.patient.patient_id);
      if (patients.size() != size_t(o.size.matched) || c.size() != size_t(10 * o.size.matched))
        return internal_error("stage 1 keeps " + std::to_string(patients.size()) + " patients and " +
                              std::to_string(c.size()) + " structures, expected " + std::to_string(o.size.matched) +
                              " and " + std::to_string(10 * o.size.matched));
      candidates = c.size();
    }
  }

  std::vector<ServerRun> runs;
  for (int i = 0; i < o.runs; ++i) {
    note("soiq-bench query: cold and warm, run %s\n", std::to_string(i + 1));
    SOIQ_ASSIGN_OR_RETURN(ServerRun r, server_run(o, pristine, work.path() + "/run.db", 5));
    if (r.cold.summary.computed() != int64_t(candidates) || r.warm.back().summary.cache_hits() != int64_t(candidates))
      return internal_error("cold computed " + std::to_string(r.cold.summary.computed()) + ", warm hit " +
                            std::to_string(r.warm.back().summary.cache_hits()) + " of " + std::to_string(candidates));
    runs.push_back(std::move(r));
  }

  note("soiq-bench query: concurrent clients\n");
  std::vector<Throughput> load;
  {
    // On the warm database of the last run.
    SoiqdChild server(o.soiqd, work.path() + "/run.db", {"--workers", std::to_string(o.workers)});
    if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
    SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(server.address()));
    SOIQ_RETURN_IF_ERROR(timed_query(c, benchmark_request()).status());  // warms the page cache
    for (int clients : {1, 2, 4, 8}) {
      SOIQ_ASSIGN_OR_RETURN(Throughput t, throughput(server.address(), clients, o.seconds));
      load.push_back(t);
    }
  }

  note("soiq-bench query: where the cold time goes (in-process, one thread)\n");
  fs::copy_file(pristine, work.path() + "/breakdown.db", fs::copy_options::overwrite_existing);
  SOIQ_ASSIGN_OR_RETURN(const ColdBreakdown b, cold_breakdown(work.path() + "/breakdown.db", query_stage1_filter()));
  // The server's rows hold the values computed in-process, exactly (same functions, same inputs).
  for (const ServerRun& r : runs) {
    for (const Timed* t : {&r.cold, &r.warm.back()}) {
      if (t->kept.size() != size_t(std::min<int64_t>(20, int64_t(candidates))))
        return internal_error("the query returned " + std::to_string(t->kept.size()) + " rows");
      for (const v1::QueryRow& row : t->kept) {
        auto it = b.values.find(row.structure().id());
        for (int i = 0; i < 3; ++i) {
          if (it == b.values.end() || row.values(i).value_size() != 1 ||
              row.values(i).value(0) != it->second[size_t(i)])
            return internal_error("structure " + std::to_string(row.structure().id()) + ": the server's " +
                                  row.values(i).name() + " differs from the in-process value");
        }
      }
    }
  }

  // --- the report ---------------------------------------------------------------------------
  std::vector<double> s1_server, s1_client, cold_client, cold_stage2, warm_client, warm_total;
  for (const ServerRun& r : runs) {
    s1_server.push_back(r.stage1.summary.stage1_ms());
    s1_client.push_back(r.stage1.client_ms);
    cold_client.push_back(r.cold.client_ms);
    cold_stage2.push_back(r.cold.summary.stage2_ms());
    for (const Timed& w : r.warm) {
      warm_client.push_back(w.client_ms);
      warm_total.push_back(w.summary.total_ms());
    }
  }
  const Stats s1 = stats(stage1_ms), s1s = stats(s1_server), s1c = stats(s1_client), cc = stats(cold_client),
              cs2 = stats(cold_stage2), wc = stats(warm_client), wt = stats(warm_total);
  auto ok = [](double v, double limit) { return v < limit ? "met" : "**not met**"; };
  const int64_t matched_patients = o.size.matched;
  std::printf(
      "Cohort: %d patients (sex F/M ~50/50, born 1930-2005, one study 2010-2025, MR 50 %% / CT 35 %% / PT 15 %%);\n"
      "stage 1 (F, MR, study 2020-2023, age at study 60-75) keeps exactly %lld of them: %zu structures\n"
      "(hippocampus, amygdala, caudate, putamen, thalamus, L and R; deformed ellipsoids of %lld-%lld triangles,\n"
      "checked closed with core/geometry/mesh_defects), each study with a %lldx%lldx%lld MR image of 2 mm. The other\n"
      "patients have one structure each on %d shared surface blobs. Database: %.0f MiB. soiqd: --workers %d.\n\n",
      o.size.patients, (long long)matched_patients, candidates, (long long)min_t, (long long)max_t,
      (long long)o.size.image_dims[0], (long long)o.size.image_dims[1], (long long)o.size.image_dims[2],
      o.size.background_blobs, db_mib, o.workers);
  std::printf(
      "Query: `voxel_volume_mm3, sphericity, mean[shell:3, MR]` of every candidate, ordered by\n"
      "voxel_volume_mm3 descending, limit 20, on the default grid (1 mm, axis-aligned, margin grown for the\n"
      "shell), nearest-neighbour sampling of the MR image.\n\n");
  std::printf("| load | items | time | rate |\n|---|---:|---:|---:|\n");
  std::printf("| background patients, SqliteStore::add_structure on tmpfs | %lld | %.1f s | %.0f patients/s |\n",
              (long long)background->patients, background->seconds, double(background->patients) / background->seconds);
  std::printf(
      "| MR images, `upload_image` (NIfTI, 2 clients) | %lld (%.0f MiB) | %.1f s | %.1f images/s, %.1f MiB/s |\n",
      (long long)uploaded.images, double(uploaded.image_bytes) / (1 << 20), uploaded.image_seconds,
      double(uploaded.images) / uploaded.image_seconds,
      double(uploaded.image_bytes) / (1 << 20) / uploaded.image_seconds);
  std::printf(
      "| surfaces, `upload_surface` (binary PLY, 2 clients) | %lld (%.0f MiB, %.1f M triangles) | %.1f s | "
      "%.1f surfaces/s, %.1f MiB/s, %.2f M triangles/s |\n\n",
      (long long)uploaded.structures, double(uploaded.surface_bytes) / (1 << 20), double(uploaded.triangles) / 1e6,
      uploaded.surface_seconds, double(uploaded.structures) / uploaded.surface_seconds,
      double(uploaded.surface_bytes) / (1 << 20) / uploaded.surface_seconds,
      double(uploaded.triangles) / 1e6 / uploaded.surface_seconds);
  std::printf("| measure | best | median | runs | target |\n|---|---:|---:|---:|---|\n");
  std::printf("| stage 1, SqliteStore::stage1 in-process | %.1f ms | %.1f ms | %zu | < 50 ms: %s |\n", s1.best,
              s1.median, stage1_ms.size(), ok(s1.best, 50));
  std::printf("| stage 1, server's stage1_ms (feature-less query) | %.1f ms | %.1f ms | %zu | < 50 ms: %s |\n",
              s1s.best, s1s.median, s1_server.size(), ok(s1s.best, 50));
  std::printf("| stage 1, client end to end (%zu rows streamed) | %.1f ms | %.1f ms | %zu | |\n", candidates, s1c.best,
              s1c.median, s1_client.size());
  std::printf("| cold query, client end to end | %.2f s | %.2f s | %zu | < 10 s: %s |\n", cc.best / 1000,
              cc.median / 1000, cold_client.size(), ok(cc.best, 10000));
  std::printf("| cold query, server's stage2_ms | %.2f s | %.2f s | %zu | |\n", cs2.best / 1000, cs2.median / 1000,
              cold_stage2.size());
  std::printf("| warm query, client end to end | %.1f ms | %.1f ms | %zu | < 100 ms: %s |\n", wc.best, wc.median,
              warm_client.size(), ok(wc.best, 100));
  std::printf("| warm query, server's total_ms | %.1f ms | %.1f ms | %zu | |\n\n", wt.best, wt.median,
              warm_total.size());
  std::printf("Concurrent clients repeating the warm query for %.0f s each (own channel per client):\n\n", o.seconds);
  std::printf("| clients | queries | queries/s | p50 | p95 |\n|---:|---:|---:|---:|---:|\n");
  for (const Throughput& t : load)
    std::printf("| %d | %lld | %.1f | %.1f ms | %.1f ms |\n", t.clients, (long long)t.queries, t.per_second,
                t.latency.median, t.latency.p95);
  std::printf(
      "\nWhere the cold time goes: the same %lld structures (%.1f M triangles, %.1f M voxels inside, %.1f M\n"
      "in the shells), part by part in one thread of soiq-bench (cold_breakdown.h), summed:\n\n",
      (long long)b.structures, double(b.triangles) / 1e6, double(b.voxels) / 1e6, double(b.shell_voxels) / 1e6);
  std::printf("| part | total | per structure | share |\n|---|---:|---:|---:|\n");
  double sum = 0;
  for (const auto& [part, ms] : b.parts_ms)
    if (part.rfind("(before)", 0) != 0) sum += ms;
  for (const auto& [part, ms] : b.parts_ms)
    std::printf(
        "| %s | %.0f ms | %.2f ms | %s |\n", part.c_str(), ms, ms / double(b.structures),
        part.rfind("(before)", 0) == 0 ? "(not in sum)" : (std::to_string(int(100 * ms / sum + 0.5)) + " %").c_str());
  std::printf("| **sum (server's path)** | %.0f ms | %.2f ms | |\n", sum, sum / double(b.structures));
  std::printf("| whole pass, one thread (stage 1 %.0f ms and the (before) parts included) | %.0f ms | | |\n",
              b.stage1_ms, b.total_ms);
  std::printf("| server's cold stage 2 on %d workers (best) | %.0f ms | | |\n\n", o.workers, cs2.best);
  return ok_status();
}

}  // namespace

int run_query_bench(const CliArgs& args) {
  Result<Options> o = parse(args);
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
