#pragma once
// The Store (store.h) written once in SQL for every backend: records, their rules and the stage-1
// rows, on a SqlSession (sql_session.h) that the backend opens inside one transaction per method.
// SqliteStore (db/sqlite/) and PgStore (db/postgres/) derive from it and supply the connections
// and transactions; the conformance suite (tests/db/store_conformance_test.cpp) runs on both.
//
// Semantics a caller must know, beyond store.h, the same in every backend:
//   - Page sizes: 0 -> 100, above 1000 -> 1000, negative -> INVALID_ARGUMENT. Page tokens are
//     opaque keyset tokens (page_token.h): patients are listed by patient_id, studies by
//     study_uid, structures by id; a token of another list -> INVALID_ARGUMENT.
//   - Ages: StudyRecord::age_years is the given age when one was stored, else computed from the
//     patient's birth date and the study date as whole years plus the fraction of the current
//     year of life (age_years.h), and recomputed when either date changes.
//   - Identifiers (patient_id, study_uid, structure name) must be non-empty; sex is "", "M", "F" or
//     "O"; laterality "", "L" or "R"; dates "" or YYYYMMDD. Anything else -> INVALID_ARGUMENT.
//   - Globs are SQLite GLOB patterns (*, ?, [...]), case-sensitive except the structure name, which
//     is matched in ASCII lower case; text compares in byte order.
//   - stage1 fills every field of its candidates, the counts of patient and study included.
//   - Surface and image sha256 values are trusted to match their blobs (the server computes them
//     with encode_surface / encode_image); they must be 64 lower-case hex digits.

#include <functional>
#include <string>
#include <vector>

#include "db/sql/sql_session.h"
#include "db/store.h"

namespace soiq::db {

// One table's rows and the sha256 of their canonical bytes, in key order (SqlStore::table_digests).
struct TableDigest {
  std::string table;
  int64_t rows = 0;
  std::string sha256;
};

// One stored blob, cached value or kept instance as it is stored, for soiq-admin verify
// (SqlStore::scan_stored).
enum class StoredKind { kSurface, kImage, kCachedValue, kInstanceFile, kInstance };
struct StoredItem {
  StoredKind kind = StoredKind::kSurface;
  std::string key;                     // a surface's, image's or instance file's sha256; a cached
                                       // value's cache key; an instance's SOP Instance UID
  std::string entry;                   // a cached value's entry
  std::string surface_sha256;          // a cached value's surface
  std::string bytes;                   // the blob, the value or the file
  std::vector<int64_t> structure_ids;  // a surface's structures
  std::string series_uid;              // an image or instance file: the first series that holds
                                       // it ("" for none); an instance's series
  ImageGeometry geometry;              // an image's grid, which the blob needs to be decoded
  InstanceRecord instance;             // an instance's row, and its metadata_crc32 column: sound when
  int64_t instance_crc32 = 0;          // instance_row_crc32(instance) is that
};

// What an instance's metadata_crc32 column holds: the CRC-32 (db/crc32.h) of its whole row, the
// SOP Instance UID, series uid, slice, file sha256 and size and the metadata, so that a flipped
// bit in any of them, or a row read under another instance, fails the check
// (sql_store_instances.cpp).
uint32_t instance_row_crc32(const InstanceRecord& r);

class SqlStore : public Store {
 public:
  // Copies every record (patients to the feature cache, keys included) into `to`, an empty store of
  // either backend, in one transaction on each side; `progress(table, rows copied)` as it goes.
  // FAILED_PRECONDITION when `to` holds records. The replicas' running state is not copied. Call
  // to.after_bulk_load() after it.
  Status copy_to(SqlStore& to, const std::function<void(const std::string& table, int64_t rows)>& progress);
  // Tidies up after a bulk load such as copy_to: PostgreSQL vacuums and analyzes (hint bits and
  // statistics set once, instead of by the first queries); SQLite needs nothing.
  virtual Status after_bulk_load() { return ok_status(); }
  // Each record table's row count and digest: equal in two stores exactly when they hold the same
  // records (soiq-admin migrate compares them after a copy).
  Result<std::vector<TableDigest>> table_digests();
  // Every stored item of `kind` to `visit`, in key order, each read in a read transaction of its
  // own (cached values and instances a page at a time), so that a scrub of a large store beside a
  // running soiqd holds no snapshot for long; `visit` runs outside them. An item removed meanwhile
  // is not visited. Stops at, and returns, the first error of `visit`. Reads only columns every schema
  // version has, and a table a later version added (the instances') as empty when it is missing,
  // so a store opened read only and not migrated can be scanned.
  Status scan_stored(StoredKind kind, const std::function<Status(const StoredItem&)>& visit);

  Result<ImportedBatch> import_batch(const ImportBatch& b) override;
  Result<int64_t> remove(const Removal& r) override;
  Status put_cached_features(const std::string& surface_sha256, const std::vector<CachedFeature>& entries) override;
  Status put_cached_features(const std::vector<SurfaceFeatures>& batch) override;
  Status put_precomputed(const std::vector<Precomputed>& batch) override;
  Result<int64_t> requeue_precompute(int definitions_version, PrecomputedSet set) override;

  Result<PatientRecord> get_patient(const std::string& patient_id) override;
  Result<Page<PatientRecord>> list_patients(const PatientFilter& f, const PageRequest& p) override;
  Result<StudyRecord> get_study(const std::string& study_uid) override;
  Result<Page<StudyRecord>> list_studies(const std::string& patient_id, const PageRequest& p) override;
  Result<SeriesRecord> get_series(const std::string& series_uid) override;
  Result<std::vector<SeriesRecord>> list_series(const std::string& study_uid) override;
  Result<std::map<std::string, std::vector<SeriesRecord>>> series_of_studies(
      const std::vector<std::string>& study_uids) override;
  Result<StructureRecord> get_structure(int64_t id) override;
  Result<Page<StructureRecord>> list_structures(const StructureFilter& f, const PageRequest& p) override;
  Result<std::vector<StudyHit>> search_studies(const StudySearch& s) override;
  Result<std::vector<SeriesHit>> search_series(const SeriesSearch& s) override;
  Result<std::string> get_blob(BlobKind kind, const std::string& key) override;
  Result<std::vector<InstanceRecord>> list_instances(const std::string& series_uid) override;
  Result<std::vector<Candidate>> stage1(const Stage1Filter& f, int64_t limit) override;
  Result<std::vector<CachedFeature>> cached_features(const std::vector<std::string>& keys,
                                                     const std::vector<std::string>& entries) override;
  Result<Counts> counts() override;
  Result<std::vector<StructureRecord>> precompute_queue(int64_t limit) override;
  Result<int> replica_heartbeat(const std::string& replica_id, int64_t live_ms) override;
  Result<std::string> first_live_replica(int64_t live_ms) override;
  Status post_stage2_work(const std::string& replica_id, const std::string& query_id, const std::string& ask,
                          const std::vector<int64_t>& structure_ids) override;
  Result<std::vector<Stage2Work>> claim_stage2_work(const std::string& replica_id, int64_t limit,
                                                    int64_t live_ms) override;
  Status finish_stage2_work(const std::string& query_id, int64_t structure_id) override;
  Result<int64_t> stage2_work_left(const std::string& query_id) override;
  Status drop_stage2_work(const std::string& query_id) override;
  using Store::cached_features;
  using Store::put_precomputed;

 protected:
  // Units of work the backend provides: `fn` runs inside one transaction on a session this thread
  // holds alone; a write is retried or serialised as the backend needs, a read sees one snapshot.
  // read_one is for a single statement (a backend may skip BEGIN and COMMIT for it).
  virtual Status read(const std::function<Status(SqlSession&)>& fn) = 0;
  virtual Status write(const std::function<Status(SqlSession&)>& fn) = 0;
  virtual Status read_one(const std::function<Status(SqlSession&)>& fn) { return read(fn); }
  // A write whose statements decide by themselves (ON CONFLICT, SKIP LOCKED): the stage-2 queue,
  // heartbeats, feature-cache batches. A backend may run it at a lighter isolation than write().
  // Default write().
  virtual Status write_queue(const std::function<Status(SqlSession&)>& fn);
  // Writes the surfaces' feature-cache entries inside a write (put_cached_features, put_precomputed):
  // an upsert per entry, skipping a surface that is gone. A backend may do it in fewer statements.
  // Inputs are checked (validate_cache_entries).
  virtual Status upsert_cached_features(SqlSession& c, const std::vector<SurfaceFeatures>& batch);

 private:
  Result<int64_t> remove_structure(int64_t id);
  Result<int64_t> remove_patient(const std::string& patient_id);
  Result<std::string> image_blob(const std::string& series_uid);
  Result<std::string> surface_blob(const std::string& sha256);
  Result<std::string> instance_file(const std::string& sha256);

  // The one row `sql` finds with `key` bound as ?1, made into a T by `make(SqlStatement&)`;
  // NOT_FOUND with `missing` as the message when there is none (sql_store_reads.cpp).
  template <typename T, typename Key, typename Make>
  Result<T> one_row(const char* sql, const Key& key, const Make& make, const std::string& missing);
};

}  // namespace soiq::db
