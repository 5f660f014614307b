#pragma once
// The Store (store.h) on one SQLite file: DESIGN.md "Storage". Schema and migrations in
// schema_migrations.cpp; the SQL of each group of methods in sqlite_store_*.cpp.
//
// Threads and mutual exclusion: every method may be called from any number of threads. Writes go
// through one writer connection guarded by a mutex (SQLite has one writer at a time anyway, and
// BEGIN IMMEDIATE makes each write take the lock up front). Reads take a connection from a pool
// of `read_connections` readers (waiting when all are busy); WAL lets them run while a write is in
// progress, and each read sees one committed snapshot. A write is visible to every read that
// starts after the write method returned.
//
// Other processes may open the same file (e.g. a backup or the CLI); their locks count against
// the busy timeout, past which a method returns UNAVAILABLE.
//
// Semantics a caller must know, beyond store.h:
//   - Page sizes: 0 -> 100, above 1000 -> 1000, negative -> INVALID_ARGUMENT. Page tokens are
//     opaque keyset tokens (page_token.h): patients are listed by patient_id, studies by
//     study_uid, structures by id; a token of another list -> INVALID_ARGUMENT.
//   - Ages: StudyRecord::age_years is the given age when one was stored, else computed from the
//     patient's birth date and the study date as whole years plus the fraction of the current
//     year of life (age_years.h), and recomputed when either date changes.
//   - Identifiers (patient_id, study_uid, structure name) must be non-empty; sex is "", "M", "F" or
//     "O"; laterality "", "L" or "R"; dates "" or YYYYMMDD. Anything else -> INVALID_ARGUMENT.
//   - Globs are SQLite GLOB patterns (*, ?, [...]), case-sensitive except the structure name, which
//     is matched in ASCII lower case.
//   - stage1 fills every field of its candidates, the counts of patient and study included.
//   - Surface and image sha256 values are trusted to match their blobs (the server computes them
//     with encode_surface / encode_image); they must be 64 lower-case hex digits.

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "db/sqlite/sqlite_connection.h"
#include "db/store.h"

namespace soiq::db {

struct SqliteOptions {
  int busy_timeout_ms = 5000;  // how long a method waits for another process's lock
  int read_connections = 4;    // >= 1; more than the worker threads that read at once gains nothing
  int cache_mib = 64;          // page cache per connection, so stage 1 reads memory, not the file
};

class SqliteStore : public Store {
 public:
  // Opens (creating if absent) the database at `path` and migrates it to the current schema.
  // FAILED_PRECONDITION (naming the path) when the file is not a SQLite database or cannot be
  // opened, or when its schema version is newer than this code knows (both versions named).
  // INVALID_ARGUMENT for bad options.
  static Result<std::unique_ptr<SqliteStore>> open(const std::string& path, const SqliteOptions& options);
  ~SqliteStore() override;

  Result<ImportedBatch> import_batch(const ImportBatch& b) override;
  Result<int64_t> remove(const Removal& r) override;
  Status put_cached_features(const std::string& surface_sha256, const std::vector<CachedFeature>& entries) override;
  Status put_cached_features(const std::vector<SurfaceFeatures>& batch) override;

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
  Status put_precomputed(const std::vector<Precomputed>& batch) override;
  using Store::cached_features;
  using Store::put_precomputed;
  Result<int64_t> requeue_precompute(int definitions_version) override;

  // The schema version of the open database (latest_schema_version() after open).
  Result<int> schema_version();
  // The EXPLAIN QUERY PLAN lines ("SEARCH r USING INDEX …") of stage1's id query for `f`: for the
  // tests that every stage-1 filter is an index search, and for diagnosing a slow one.
  Result<std::vector<std::string>> stage1_plan(const Stage1Filter& f, int64_t limit);

 private:
  SqliteStore() = default;

  Result<int64_t> remove_structure(int64_t id);
  Result<int64_t> remove_patient(const std::string& patient_id);
  Result<std::string> image_blob(const std::string& series_uid);
  Result<std::string> surface_blob(const std::string& sha256);

  // The one row `sql` finds with `key` bound as ?1, made into a T by `make(Statement&)`; NOT_FOUND
  // with `missing` as the message when there is none. One read transaction (sqlite_store_reads.cpp).
  template <typename T, typename Key, typename Make>
  Result<T> one_row(const char* sql, const Key& key, const Make& make, const std::string& missing);

  // Units of work: fn runs inside one transaction on a connection this thread holds alone.
  Status read(const std::function<Status(Connection&)>& fn);
  Status write(const std::function<Status(Connection&)>& fn);

  std::mutex writer_mutex_;
  std::unique_ptr<Connection> writer_;

  std::mutex readers_mutex_;
  std::condition_variable reader_free_;
  std::vector<std::unique_ptr<Connection>> readers_;
  std::vector<Connection*> free_readers_;
};

}  // namespace soiq::db
