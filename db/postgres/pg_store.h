#pragma once
// The Store (store.h) on a PostgreSQL database that several soiqd replicas may share:
// DESIGN.md "Storage", docs/SCALE_OUT.md. The schema (pg_schema.h) is SQLite's, table for table;
// the SQL the two backends share is in db/sql/, and each method means what SqliteStore's does
// (sqlite_store.h: page sizes and tokens, ages, identifiers, globs), which the conformance suite
// (tests/db/store_conformance_test.cpp) holds both to.
//
// Threads, replicas and transactions: every method may be called from any number of threads, in
// any number of processes on the same database. A method leases a connection from the replica's
// pool (pg_pool.h; DEADLINE_EXCEEDED when none comes free in time) for its whole transaction.
//   - Writes run SERIALIZABLE: they read (is this study another patient's? is this surface stored?)
//     before they write, and two replicas importing the same patient at once must not both insert
//     it. PostgreSQL aborts one of two conflicting transactions (SQLSTATE 40001), which runs again
//     after a random wait (pg_transaction), so callers see success or a real error.
//   - Reads of several statements run in one REPEATABLE READ READ ONLY snapshot (a page and its
//     counts agree); reads of one statement run alone.
//   - Blobs travel in binary, never as hex text.
//
// Beyond SqliteStore: text must be UTF-8 (PostgreSQL refuses other bytes: INVALID_ARGUMENT), and a
// blob is at most 1 GiB (RESOURCE_EXHAUSTED).

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "db/postgres/pg_pool.h"
#include "db/store.h"

namespace soiq::db {

struct PgOptions {
  int connections = 8;                          // the pool's size (soiqd --db-connections)
  std::chrono::milliseconds lease_wait{30000};  // how long a method waits for a connection
  int write_attempts = 10;                      // runs of a write that keeps conflicting
};

class PgStore : public Store {
 public:
  // Connects the pool to `conninfo` (a postgresql:// URI or libpq key=value pairs) and migrates the
  // schema. UNAVAILABLE naming the server when it cannot be reached; FAILED_PRECONDITION when its
  // schema is newer than this code knows; INVALID_ARGUMENT for bad options.
  static Result<std::unique_ptr<PgStore>> open(const std::string& conninfo, const PgOptions& options);

  Result<ImportedBatch> import_batch(const ImportBatch& b) override;
  Result<int64_t> remove(const Removal& r) override;
  Status put_cached_features(const std::string& surface_sha256, const std::vector<CachedFeature>& entries) override;
  Status put_cached_features(const std::vector<SurfaceFeatures>& batch) override;
  Status put_precomputed(const std::vector<Precomputed>& batch) override;
  Result<int64_t> requeue_precompute(int definitions_version) override;

  Result<PatientRecord> get_patient(const std::string& patient_id) override;
  Result<Page<PatientRecord>> list_patients(const PatientFilter& f, const PageRequest& p) override;
  Result<StudyRecord> get_study(const std::string& study_uid) override;
  Result<Page<StudyRecord>> list_studies(const std::string& patient_id, const PageRequest& p) override;
  Result<SeriesRecord> get_series(const std::string& series_uid) override;
  Result<std::vector<SeriesRecord>> list_series(const std::string& study_uid) override;
  Result<StructureRecord> get_structure(int64_t id) override;
  Result<Page<StructureRecord>> list_structures(const StructureFilter& f, const PageRequest& p) override;
  Result<std::string> get_blob(BlobKind kind, const std::string& key) override;
  Result<std::vector<Candidate>> stage1(const Stage1Filter& f, int64_t limit) override;
  Result<std::vector<CachedFeature>> cached_features(const std::vector<std::string>& keys,
                                                     const std::vector<std::string>& entries) override;
  Result<Counts> counts() override;
  Result<std::vector<StructureRecord>> precompute_queue(int64_t limit) override;
  using Store::cached_features;
  using Store::put_precomputed;

 private:
  PgStore() = default;

  // Units of work on a leased connection: `fn` runs in one SERIALIZABLE transaction (retried),
  // one read-only snapshot, or alone (one statement: its own snapshot, no BEGIN and COMMIT).
  Status write(const std::function<Status(PgConnection&)>& fn);
  Status read(const std::function<Status(PgConnection&)>& fn);
  Status read_one(const std::function<Status(PgConnection&)>& fn);

  std::unique_ptr<PgPool> pool_;
  PgOptions options_;
};

}  // namespace soiq::db
