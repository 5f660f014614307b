#include "bench/replicas_bench.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bench/clock.h"
#include "bench/query_cohort.h"
#include "bench/query_load.h"
#include "bench/query_runs.h"
#include "server/app/store_admin.h"
#include "tests/support/postgres_process.h"
#include "tests/support/soiqd_process.h"
#include "tests/support/temp_dir.h"

namespace soiq::bench {
namespace {

namespace fs = std::filesystem;

void note(const std::string& s) { std::fprintf(stderr, "soiq-bench replicas: %s\n", s.c_str()); }

struct ReplicasOptions {
  QueryCohortSize size;
  std::string soiqd = SOIQD_BINARY;
  int workers = 2;
  double seconds = 3;
  int stage1_patients = 1000000;  // the second cohort, for stage 1 alone at scale
};

struct ColdRun {
  int replicas = 0;
  double client_ms = 0;
  int64_t computed = 0;
  std::vector<int64_t> shares;  // items each replica computed for the query
};

// One soiqd alone on a backend: the cold benchmark query on a fresh copy of the loaded store, then
// the warm query repeated by 1 and by 8 clients.
struct SingleServer {
  double cold_client_ms = 0, cold_stage2_ms = 0;
  Throughput one, eight;
};

struct Figures {
  LoadFigures ingest_sqlite, ingest_postgres;
  double migrate_s = 0;
  int64_t migrated_rows = 0;
  Stats stage1_sqlite, stage1_postgres;
  int64_t candidates = 0;
  std::vector<ColdRun> cold;
  Throughput load;
  SingleServer single_sqlite, single_postgres;
  int64_t million_patients = 0, million_structures = 0, million_candidates = 0, million_rows = 0;
  Stats million_sqlite, million_postgres;
};

// A PostgreSQL database made from `template_db` (a file-level copy: fast, and every run starts equal).
Status make_database(const testing::PostgresProcess& pg, const std::string& name, const std::string& template_db) {
  PGconn* c = PQconnectdb(pg.conninfo("postgres").c_str());
  const std::string sql = "CREATE DATABASE " + name + (template_db.empty() ? "" : " TEMPLATE " + template_db);
  PGresult* r = PQexec(c, sql.c_str());
  const bool ok = PQresultStatus(r) == PGRES_COMMAND_OK;
  const std::string why = PQresultErrorMessage(r);
  PQclear(r);
  PQfinish(c);
  return ok ? ok_status() : internal_error(sql + ": " + why);
}

std::string uri(const testing::PostgresProcess& pg, const std::string& db) {
  return "postgresql://" + std::string(testing::PostgresProcess::kUser) + "@127.0.0.1:" + std::to_string(pg.port()) +
         "/" + db;
}

std::unique_ptr<testing::SoiqdProcess> replica(const ReplicasOptions& o, const testing::TempDir& dir,
                                               const std::string& db, const std::string& id) {
  return std::make_unique<testing::SoiqdProcess>(
      dir.file(id + ".log.db"),
      std::vector<std::string>{"--db", db, "--workers", std::to_string(o.workers), "--replica-id", id}, o.soiqd);
}

int64_t items_computed(const std::string& log) {
  const size_t at = log.rfind("items_computed=");
  return at == std::string::npos ? -1 : std::atoll(log.c_str() + at + 15);
}

Result<Stats> stage1_through(const std::string& address, int64_t& candidates) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(address));
  std::vector<double> ms;
  for (int i = 0; i < 21; ++i) {
    SOIQ_ASSIGN_OR_RETURN(const TimedQuery t, timed_query(c, stage1_only_request()));
    if (i > 0) ms.push_back(t.client_ms);  // the first warms the caches
    candidates = t.summary.stage1_candidates();
  }
  return stats(ms);
}

Result<SingleServer> single_server(const ReplicasOptions& o, const std::string& db, const std::string& log_db) {
  testing::SoiqdProcess server(log_db, {"--db", db, "--workers", std::to_string(o.workers)}, o.soiqd);
  if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(server.address()));
  SingleServer out;
  SOIQ_ASSIGN_OR_RETURN(const TimedQuery cold, timed_query(c, benchmark_request()));
  out.cold_client_ms = cold.client_ms;
  out.cold_stage2_ms = cold.summary.stage2_ms();
  SOIQ_ASSIGN_OR_RETURN(out.one, throughput({server.address()}, 1, o.seconds));
  SOIQ_ASSIGN_OR_RETURN(out.eight, throughput({server.address()}, 8, o.seconds));
  if (server.terminate() != 0) return internal_error("soiqd did not stop cleanly: " + server.log());
  return out;
}

// Stage 1 alone over `o.stage1_patients` patients (one structure each, the matched ones with their
// 10), in SQLite and, migrated, in PostgreSQL: the index search at scale on both backends.
Status stage1_at_scale(const ReplicasOptions& o, const testing::TempDir& dir, const testing::PostgresProcess& pg,
                       Figures& f) {
  QueryCohortSize size = o.size;
  size.patients = o.stage1_patients;
  const std::vector<CohortPatient> cohort = query_cohort_patients(size, 20250409);
  note(std::to_string(size.patients) + " patients through SqliteStore, for stage 1 at scale");
  const std::string sqlite = dir.file("million.db");
  SOIQ_ASSIGN_OR_RETURN(const LoadFigures background, load_background(sqlite, cohort, size));
  f.million_structures = background.structures;
  {
    testing::SoiqdProcess server(sqlite, {"--workers", std::to_string(o.workers)}, o.soiqd);
    if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
    SOIQ_ASSIGN_OR_RETURN(const LoadFigures matched,
                          upload_matched(server.address(), dir.path().string(), cohort, size, 2));
    f.million_structures += matched.structures;
    if (server.terminate() != 0) return internal_error("soiqd did not stop cleanly: " + server.log());
  }
  note("migrated to PostgreSQL");
  SOIQ_RETURN_IF_ERROR(make_database(pg, "million", ""));
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::TableDigest> digests,
                        server::migrate_store({server::StoreLocation::Kind::kSqlite, sqlite},
                                              {server::StoreLocation::Kind::kPostgres, uri(pg, "million")}, {}));
  for (const db::TableDigest& d : digests) f.million_rows += d.rows;
  f.million_patients = size.patients;
  for (const bool on_postgres : {false, true}) {
    testing::SoiqdProcess server(sqlite, {"--db", on_postgres ? uri(pg, "million") : sqlite}, o.soiqd);
    if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
    SOIQ_ASSIGN_OR_RETURN((on_postgres ? f.million_postgres : f.million_sqlite),
                          stage1_through(server.address(), f.million_candidates));
  }
  return ok_status();
}

Status run(const ReplicasOptions& o, Figures& f) {
  testing::TempDir dir;
  const std::vector<CohortPatient> cohort = query_cohort_patients(o.size, 20250409);
  note("background patients through SqliteStore");
  const std::string sqlite = dir.file("cohort.db");
  SOIQ_RETURN_IF_ERROR(load_background(sqlite, cohort, o.size).status());

  testing::PostgresProcess pg;
  if (const std::string why = pg.start(); !why.empty()) return internal_error("PostgreSQL: " + why);
  SOIQ_RETURN_IF_ERROR(make_database(pg, "ingest", ""));
  for (const bool on_postgres : {false, true}) {
    note(std::string("matched patients uploaded through soiqd on ") + (on_postgres ? "PostgreSQL" : "SQLite"));
    testing::SoiqdProcess server(
        on_postgres ? dir.file("ingest.log.db") : sqlite,
        {"--db", on_postgres ? uri(pg, "ingest") : sqlite, "--workers", std::to_string(o.workers)}, o.soiqd);
    if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
    SOIQ_ASSIGN_OR_RETURN(LoadFigures up, upload_matched(server.address(), dir.path().string(), cohort, o.size, 2));
    (on_postgres ? f.ingest_postgres : f.ingest_sqlite) = up;
    if (server.terminate() != 0) return internal_error("soiqd did not stop cleanly: " + server.log());
  }

  note("the loaded store copied to PostgreSQL (soiq-admin migrate)");
  SOIQ_RETURN_IF_ERROR(make_database(pg, "pristine", ""));
  const Clock::time_point t0 = Clock::now();
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::TableDigest> digests,
                        server::migrate_store({server::StoreLocation::Kind::kSqlite, sqlite},
                                              {server::StoreLocation::Kind::kPostgres, uri(pg, "pristine")}, {}));
  f.migrate_s = ms_since(t0) / 1000;
  for (const db::TableDigest& d : digests) f.migrated_rows += d.rows;

  note("stage 1 through soiqd on each backend");
  // On a copy: a replica leaves its heartbeat row behind, which the cold runs' copies must not hold.
  SOIQ_RETURN_IF_ERROR(make_database(pg, "stage1", "pristine"));
  for (const bool on_postgres : {false, true}) {
    testing::SoiqdProcess server(sqlite, {"--db", on_postgres ? uri(pg, "stage1") : sqlite}, o.soiqd);
    if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
    SOIQ_ASSIGN_OR_RETURN((on_postgres ? f.stage1_postgres : f.stage1_sqlite),
                          stage1_through(server.address(), f.candidates));
  }

  note("one soiqd on each backend: the cold query, then the warm query by 1 and 8 clients");
  const std::string sqlite_copy = dir.file("single.db");
  fs::copy_file(sqlite, sqlite_copy, fs::copy_options::overwrite_existing);
  SOIQ_ASSIGN_OR_RETURN(f.single_sqlite, single_server(o, sqlite_copy, sqlite_copy));
  fs::remove(sqlite_copy);
  SOIQ_RETURN_IF_ERROR(make_database(pg, "single", "pristine"));
  SOIQ_ASSIGN_OR_RETURN(f.single_postgres, single_server(o, uri(pg, "single"), dir.file("single.log.db")));

  for (int n = 1; n <= 3; ++n) {
    note("the cold query on " + std::to_string(n) + " replica(s)");
    const std::string db = "cold" + std::to_string(n);
    SOIQ_RETURN_IF_ERROR(make_database(pg, db, "pristine"));
    std::vector<std::unique_ptr<testing::SoiqdProcess>> replicas;
    for (int r = 0; r < n; ++r) {
      replicas.push_back(replica(o, dir, uri(pg, db), "r" + std::to_string(n) + std::to_string(r)));
      if (replicas.back()->address().empty()) return internal_error("soiqd did not start: " + replicas.back()->log());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // every replica has heard the others
    SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(replicas[0]->address()));
    SOIQ_ASSIGN_OR_RETURN(const TimedQuery cold, timed_query(c, benchmark_request()));
    ColdRun run{n, cold.client_ms, cold.summary.computed(), {}};
    if (n == 3) {
      note("8 clients against the three replicas");
      std::vector<std::string> addresses;
      for (const auto& r : replicas) addresses.push_back(r->address());
      SOIQ_ASSIGN_OR_RETURN(f.load, throughput(addresses, 8, o.seconds));
    }
    for (auto& r : replicas) {
      if (r->terminate() != 0) return internal_error("soiqd did not stop cleanly: " + r->log());
      run.shares.push_back(items_computed(r->log()));
    }
    f.cold.push_back(run);
  }
  if (o.stage1_patients > 0) SOIQ_RETURN_IF_ERROR(stage1_at_scale(o, dir, pg, f));
  return ok_status();
}

void print(const ReplicasOptions& o, const Figures& f) {
  std::printf("### Replicas on PostgreSQL\n\n");
  std::printf("Cohort: %lld patients (%lld matched); soiqd `--workers %d`; PostgreSQL 15 on the same machine,\n",
              (long long)o.size.patients, (long long)o.size.matched, o.workers);
  std::printf("over loopback TCP, started by the benchmark (fsync on, defaults otherwise).\n\n");
  std::printf("| measure | SQLite | PostgreSQL |\n|---|---:|---:|\n");
  auto per_s = [](const LoadFigures& l) { return l.seconds > 0 ? double(l.structures + l.images) / l.seconds : 0.0; };
  std::printf("| ingest through soiqd: %lld surfaces + %lld images, uploads/s | %.1f | %.1f |\n",
              (long long)f.ingest_sqlite.structures, (long long)f.ingest_sqlite.images, per_s(f.ingest_sqlite),
              per_s(f.ingest_postgres));
  std::printf("| stage 1 through soiqd, %lld candidates: best / median ms | %.1f / %.1f | %.1f / %.1f |\n\n",
              (long long)f.candidates, f.stage1_sqlite.best, f.stage1_sqlite.median, f.stage1_postgres.best,
              f.stage1_postgres.median);
  std::printf("Migration SQLite -> PostgreSQL (`soiq-admin migrate`, verified): %lld rows in %.1f s.\n\n",
              (long long)f.migrated_rows, f.migrate_s);
  const SingleServer &sq = f.single_sqlite, &pq = f.single_postgres;
  auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
  const double cold_ratio = ratio(pq.cold_client_ms, sq.cold_client_ms);
  const double load_ratio = ratio(pq.eight.per_second, sq.eight.per_second);
  std::printf("One soiqd (`--workers %d`) on each backend, on a fresh copy of the loaded store; the warm query\n",
              o.workers);
  std::printf("repeated for %.0f s by 1 client, then by 8:\n\n", o.seconds);
  std::printf("| measure | SQLite | PostgreSQL | PostgreSQL / SQLite | target |\n|---|---:|---:|---:|---|\n");
  std::printf("| cold query, client ms (server's stage2_ms) | %.0f (%.0f) | %.0f (%.0f) | %.2fx | <= 1.3x: %s |\n",
              sq.cold_client_ms, sq.cold_stage2_ms, pq.cold_client_ms, pq.cold_stage2_ms, cold_ratio,
              cold_ratio <= 1.3 ? "met" : "**not met**");
  std::printf("| warm query, 1 client: queries/s (p95 ms) | %.1f (%.1f) | %.1f (%.1f) | %.2fx | |\n", sq.one.per_second,
              sq.one.latency.p95, pq.one.per_second, pq.one.latency.p95, ratio(pq.one.per_second, sq.one.per_second));
  std::printf("| warm query, 8 clients: queries/s (p95 ms) | %.1f (%.1f) | %.1f (%.1f) | %.2fx | >= 0.8x: %s |\n\n",
              sq.eight.per_second, sq.eight.latency.p95, pq.eight.per_second, pq.eight.latency.p95, load_ratio,
              load_ratio >= 0.8 ? "met" : "**not met**");
  if (f.million_patients > 0) {
    std::printf("Stage 1 at scale: %lld patients (%lld structures, %lld rows migrated), stage 1 alone through\n",
                (long long)f.million_patients, (long long)f.million_structures, (long long)f.million_rows);
    std::printf("soiqd, %lld candidates, best / median of 20 ms: SQLite %.1f / %.1f, PostgreSQL %.1f / %.1f.\n\n",
                (long long)f.million_candidates, f.million_sqlite.best, f.million_sqlite.median,
                f.million_postgres.best, f.million_postgres.median);
  }
  std::printf("| cold query (%lld structures computed) | client ms | structures computed by each replica |\n",
              (long long)(f.cold.empty() ? 0 : f.cold[0].computed));
  std::printf("|---|---:|---|\n");
  for (const ColdRun& r : f.cold) {
    std::string shares;
    for (const int64_t s : r.shares) shares += (shares.empty() ? "" : " / ") + std::to_string(s);
    if (r.replicas == 1) shares = "alone: no sharing";
    std::printf("| %d replica%s | %.0f | %s |\n", r.replicas, r.replicas > 1 ? "s" : "", r.client_ms, shares.c_str());
  }
  std::printf(
      "\n8 clients, warm query, round robin over the three replicas: %.1f queries/s, p50 %.1f ms, p95 %.1f ms.\n\n",
      f.load.per_second, f.load.latency.median, f.load.latency.p95);
}

}  // namespace

int run_replicas_bench(const CliArgs& args) {
  ReplicasOptions o;
  if (args.has("--small")) {
    o.size.patients = 10000;
    o.size.matched = 10;
    o.size.max_triangles = 20000;
    o.seconds = 1;
    o.stage1_patients = 20000;
  }
  auto parsed = [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(o.size.patients, args.get_int("--patients", o.size.patients));
    SOIQ_ASSIGN_OR_RETURN(o.size.matched, args.get_int("--matched", o.size.matched));
    SOIQ_ASSIGN_OR_RETURN(o.workers, args.get_int("--workers", o.workers));
    SOIQ_ASSIGN_OR_RETURN(o.seconds, args.get_double("--seconds", o.seconds));
    SOIQ_ASSIGN_OR_RETURN(o.stage1_patients, args.get_int("--stage1-patients", o.stage1_patients));
    o.soiqd = args.get("--soiqd", o.soiqd);
    return ok_status();
  }();
  if (!parsed.ok()) {
    std::fprintf(stderr, "soiq-bench replicas: %s\n", parsed.message().c_str());
    return 2;
  }
  Figures f;
  const Status s = run(o, f);
  if (!s.ok()) {
    std::fprintf(stderr, "soiq-bench replicas: %s\n", s.to_string().c_str());
    return 1;
  }
  print(o, f);
  return 0;
}

}  // namespace soiq::bench
