#include "db/sqlite/schema_migrations.h"

#include <string>
#include <vector>

#include "db/sqlite/schema_reencode.h"
#include "db/sqlite/sqlite_statement.h"

namespace soiq::db {
namespace {

struct Migration {
  int to_version;
  const char* sql;
  // A step SQL cannot say (re-encoding blobs), run after `sql` in the same transaction.
  Status (*run)(Connection& c) = nullptr;
};

// Version 1: the whole store. Conventions:
//   - Text fields that may be unknown are '' (never NULL), so globs and equality need no NULL
//     handling; ages are NULL when unknown because they are compared as numbers.
//   - patients and studies have integer surrogate keys for fast joins; the DICOM identifiers are
//     UNIQUE (which indexes them).
//   - Large blobs are the last column, so reading the other columns never touches overflow pages.
//   - Every stage-1 filter has an index (docs/DESIGN.md "Queries"); every foreign key has an index on
//     its child column, so cascades and orphan checks are index lookups.
//   - structures.id is AUTOINCREMENT: an id is never reused after a delete, so a client's old id
//     can never name a different structure.
constexpr char kSchemaV1[] = R"sql(
CREATE TABLE patients (
  pk INTEGER PRIMARY KEY,
  patient_id TEXT NOT NULL UNIQUE,
  sex TEXT NOT NULL DEFAULT '',
  birth_date TEXT NOT NULL DEFAULT ''
);
CREATE INDEX patients_sex ON patients(sex);
CREATE INDEX patients_birth_date ON patients(birth_date);

CREATE TABLE studies (
  pk INTEGER PRIMARY KEY,
  study_uid TEXT NOT NULL UNIQUE,
  patient_pk INTEGER NOT NULL REFERENCES patients(pk) ON DELETE CASCADE,
  study_date TEXT NOT NULL DEFAULT '',
  description TEXT NOT NULL DEFAULT '',
  modality TEXT NOT NULL DEFAULT '',
  age_years REAL,
  age_given INTEGER NOT NULL DEFAULT 0  -- 1: age_years came from DICOM, else computed
);
CREATE INDEX studies_patient ON studies(patient_pk);
CREATE INDEX studies_date ON studies(study_date);
CREATE INDEX studies_age ON studies(age_years);
CREATE INDEX studies_modality ON studies(modality);
CREATE INDEX studies_description ON studies(description);

CREATE TABLE image_blobs (
  sha256 TEXT PRIMARY KEY NOT NULL,
  blob BLOB NOT NULL
);

CREATE TABLE series (
  pk INTEGER PRIMARY KEY,
  series_uid TEXT NOT NULL UNIQUE,
  study_pk INTEGER NOT NULL REFERENCES studies(pk) ON DELETE CASCADE,
  modality TEXT NOT NULL DEFAULT '',
  origin_x REAL NOT NULL, origin_y REAL NOT NULL, origin_z REAL NOT NULL,
  spacing_x REAL NOT NULL, spacing_y REAL NOT NULL, spacing_z REAL NOT NULL,
  dim_x INTEGER NOT NULL, dim_y INTEGER NOT NULL, dim_z INTEGER NOT NULL,
  -- row-major 3x3; columns are the i, j, k directions in LPS
  d00 REAL NOT NULL, d01 REAL NOT NULL, d02 REAL NOT NULL,
  d10 REAL NOT NULL, d11 REAL NOT NULL, d12 REAL NOT NULL,
  d20 REAL NOT NULL, d21 REAL NOT NULL, d22 REAL NOT NULL,
  image_sha256 TEXT NOT NULL REFERENCES image_blobs(sha256)
);
CREATE INDEX series_study ON series(study_pk, modality);
CREATE INDEX series_modality ON series(modality, study_pk);
CREATE INDEX series_image ON series(image_sha256);

CREATE TABLE surfaces (
  sha256 TEXT PRIMARY KEY NOT NULL,
  vertex_count INTEGER NOT NULL,
  triangle_count INTEGER NOT NULL,
  min_x REAL NOT NULL, min_y REAL NOT NULL, min_z REAL NOT NULL,
  max_x REAL NOT NULL, max_y REAL NOT NULL, max_z REAL NOT NULL,
  blob BLOB NOT NULL
);

CREATE TABLE structures (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  study_pk INTEGER NOT NULL REFERENCES studies(pk) ON DELETE CASCADE,
  name TEXT NOT NULL,
  laterality TEXT NOT NULL DEFAULT '',
  robust INTEGER NOT NULL DEFAULT 0,
  created_at TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  surface_sha256 TEXT NOT NULL REFERENCES surfaces(sha256)
);
CREATE INDEX structures_study ON structures(study_pk);
CREATE INDEX structures_name_lower ON structures(lower(name));
CREATE INDEX structures_laterality ON structures(laterality);
CREATE INDEX structures_surface ON structures(surface_sha256);

CREATE TABLE feature_cache (
  key TEXT NOT NULL,
  entry TEXT NOT NULL,
  surface_sha256 TEXT NOT NULL REFERENCES surfaces(sha256) ON DELETE CASCADE,
  value BLOB NOT NULL,  -- little-endian float64s
  PRIMARY KEY (key, entry)
) WITHOUT ROWID;
CREATE INDEX feature_cache_surface ON feature_cache(surface_sha256);

-- Stage 1 reads this one narrow table: a row per structure with every stage-1 filter value
-- copied from its patient, study and series. A scan of 100k rows takes ~20 ms where the join of
-- structures, studies and patients takes ~200 ms. Kept in step by the store's writes
-- (refresh_stage1_rows in sqlite_store_writes.cpp), in the same transaction; deletes cascade.
-- modalities is '/' + the study's modality + '/' + each series' modality + '/'.
CREATE TABLE stage1_rows (
  structure_id INTEGER PRIMARY KEY REFERENCES structures(id) ON DELETE CASCADE,
  patient_pk INTEGER NOT NULL,
  patient_id TEXT NOT NULL,
  sex TEXT NOT NULL,
  birth_date TEXT NOT NULL,
  age_years REAL,
  study_date TEXT NOT NULL,
  modalities TEXT NOT NULL,
  description TEXT NOT NULL,
  name_lower TEXT NOT NULL,
  laterality TEXT NOT NULL
);
CREATE INDEX stage1_rows_patient_pk ON stage1_rows(patient_pk);
CREATE INDEX stage1_rows_patient_id ON stage1_rows(patient_id);
CREATE INDEX stage1_rows_birth_date ON stage1_rows(birth_date);
CREATE INDEX stage1_rows_age ON stage1_rows(age_years);
CREATE INDEX stage1_rows_study_date ON stage1_rows(study_date);
CREATE INDEX stage1_rows_description ON stage1_rows(description);
CREATE INDEX stage1_rows_name_lower ON stage1_rows(name_lower);
)sql";

// Version 2: DICOM references, for objects derived from a series. A series keeps its Frame of
// Reference UID, its slices' SOP Class UID and SOP Instance UIDs (by slice, joined with '\\', the DICOM multi-value
// separator, which a UID cannot contain), so soiq can write a DICOM SEG that references them. A structure keeps the
// series it was converted on and, when imported, "<RT Structure Set SOP Instance UID>/<ROI number>": unique, so a
// re-import updates the structure in place (same id) instead of copying it.
constexpr char kSchemaV2[] = R"sql(
ALTER TABLE series ADD COLUMN frame_of_reference_uid TEXT NOT NULL DEFAULT '';
ALTER TABLE series ADD COLUMN sop_class_uid TEXT NOT NULL DEFAULT '';
ALTER TABLE series ADD COLUMN slice_instance_uids TEXT NOT NULL DEFAULT '';
ALTER TABLE structures ADD COLUMN source_series_uid TEXT NOT NULL DEFAULT '';
ALTER TABLE structures ADD COLUMN source_uid TEXT NOT NULL DEFAULT '';
CREATE UNIQUE INDEX structures_source_uid ON structures(source_uid) WHERE source_uid <> '';
)sql";

// Version 3: the study's DICOM Study Time, Study ID and Accession Number, so a SEG soiq exports on
// the study carries them as the study's other instances do (a RIS matches on the accession
// number). '' for studies stored before, or uploaded: the export then writes them empty.
constexpr char kSchemaV3[] = R"sql(
ALTER TABLE studies ADD COLUMN study_time TEXT NOT NULL DEFAULT '';
ALTER TABLE studies ADD COLUMN study_id TEXT NOT NULL DEFAULT '';
ALTER TABLE studies ADD COLUMN accession_number TEXT NOT NULL DEFAULT '';
)sql";

// Version 4: surface blobs in the delta-planes codec (db/surface_blob.h): decoding a version 1 (zlib)
// blob was over half of a cold query's time per structure. And each structure's surface measure for
// the memory budget (SurfaceInfo::area_bound_mm2, perimeter_bound_mm), which admission decoded and
// walked the surface for before every cold conversion; in structures, not surfaces, since a column
// added to surfaces would follow its blob and every read of it would walk the blob's overflow pages.
// Each surface is decoded once here, measured, and written again in version 2; the sha256, counts
// and bounds describe the mesh, not its codec, and stay. One transaction: a store is migrated whole
// or not at all.
constexpr char kSchemaV4[] = R"sql(
ALTER TABLE structures ADD COLUMN surface_area_bound_mm2 REAL NOT NULL DEFAULT 0;
ALTER TABLE structures ADD COLUMN surface_perimeter_bound_mm REAL NOT NULL DEFAULT 0;
)sql";

// Version 5: precompute (db/store.h), and image blobs in the delta-planes codec (reencode_image_blobs). A durable queue
// of the structures whose default features soiqd has still to compute (a restart resumes it), every stored structure
// queued; the stored shape values, by structure; and a copy of them in stage1_rows with an index each, so that a
// content filter over the whole database is an index range, not a visit of every structure. features_stored is 0 while
// a structure has no stored values: stage 1 keeps those rows for stage 2, through the partial index (an OR of two index
// searches, see sqlite_store_stage1.cpp).
constexpr char kSchemaV5[] = R"sql(
CREATE TABLE precompute_queue (
  structure_id INTEGER PRIMARY KEY REFERENCES structures(id) ON DELETE CASCADE,
  failure TEXT NOT NULL DEFAULT ''  -- '' while queued; why it failed once it has
);
CREATE INDEX precompute_queue_waiting ON precompute_queue(structure_id) WHERE failure = '';

CREATE TABLE stored_features (
  structure_id INTEGER PRIMARY KEY REFERENCES structures(id) ON DELETE CASCADE,
  definitions_version INTEGER NOT NULL,
  voxel_volume_mm3 REAL,
  surface_area_mm2 REAL,
  sphericity REAL,
  elongation REAL,
  flatness REAL,
  maximum_3d_diameter_mm REAL
);
CREATE INDEX stored_features_version ON stored_features(definitions_version);

ALTER TABLE stage1_rows ADD COLUMN features_stored INTEGER NOT NULL DEFAULT 0;
ALTER TABLE stage1_rows ADD COLUMN voxel_volume_mm3 REAL;
ALTER TABLE stage1_rows ADD COLUMN surface_area_mm2 REAL;
ALTER TABLE stage1_rows ADD COLUMN sphericity REAL;
ALTER TABLE stage1_rows ADD COLUMN elongation REAL;
ALTER TABLE stage1_rows ADD COLUMN flatness REAL;
ALTER TABLE stage1_rows ADD COLUMN maximum_3d_diameter_mm REAL;
CREATE INDEX stage1_rows_features_unstored ON stage1_rows(features_stored) WHERE features_stored = 0;
CREATE INDEX stage1_rows_voxel_volume_mm3 ON stage1_rows(voxel_volume_mm3);
CREATE INDEX stage1_rows_surface_area_mm2 ON stage1_rows(surface_area_mm2);
CREATE INDEX stage1_rows_sphericity ON stage1_rows(sphericity);
CREATE INDEX stage1_rows_elongation ON stage1_rows(elongation);
CREATE INDEX stage1_rows_flatness ON stage1_rows(flatness);
CREATE INDEX stage1_rows_maximum_3d_diameter_mm ON stage1_rows(maximum_3d_diameter_mm);

INSERT INTO precompute_queue(structure_id) SELECT id FROM structures;
)sql";

// Version 6: stage 1's range indexes carry every other structured filter column. A query driven
// by an age, study-date, birth-date or structure-name range then tests its other conditions (sex,
// modality, laterality, the other ranges) inside the index and reads no stage1_rows row at all: the
// ids are the index's rowids. Measured over 10^5 patients (age 60-75 keeps 19,706 index entries,
// 1,000 of which match): 16 ms with a table row read per entry, 2 ms covered. The indexes keep
// their names, so the plans the tests check read the same.
constexpr char kSchemaV6[] = R"sql(
DROP INDEX stage1_rows_age;
CREATE INDEX stage1_rows_age
  ON stage1_rows(age_years, study_date, birth_date, sex, laterality, modalities);
DROP INDEX stage1_rows_study_date;
CREATE INDEX stage1_rows_study_date
  ON stage1_rows(study_date, age_years, birth_date, sex, laterality, modalities);
DROP INDEX stage1_rows_birth_date;
CREATE INDEX stage1_rows_birth_date
  ON stage1_rows(birth_date, age_years, study_date, sex, laterality, modalities);
DROP INDEX stage1_rows_name_lower;
CREATE INDEX stage1_rows_name_lower
  ON stage1_rows(name_lower, age_years, study_date, birth_date, sex, laterality, modalities);
)sql";

// Version 7: replicas sharing one database, and the stage-2 work they share (db/store.h,
// docs/SCALE_OUT.md). A SQLite file has one soiqd; the tables are here so both backends run the
// same store code, and a file moved to PostgreSQL keeps its shape.
constexpr char kSchemaV7[] = R"sql(
CREATE TABLE replicas (
  id TEXT PRIMARY KEY,
  seen_ms INTEGER NOT NULL  -- the last heartbeat, by the database's clock (ms since 1970)
);
CREATE TABLE stage2_work (
  query_id TEXT NOT NULL,
  structure_id INTEGER NOT NULL,
  ask TEXT NOT NULL,
  posted_by TEXT NOT NULL,
  posted_ms INTEGER NOT NULL,
  claimed_by TEXT NOT NULL DEFAULT '',  -- '' until a replica claims it
  PRIMARY KEY (query_id, structure_id)
);
CREATE INDEX stage2_work_posted ON stage2_work(posted_ms);
)sql";

// Version 8: what DICOMweb's QIDO-RS answers with (server/http/): the patient's name (kept only when
// soiqd is started with --keep-patient-names), the series' number and description. The name index
// is on lower(): QIDO matches names case-insensitively, and a prefix becomes an index range.
constexpr char kSchemaV8[] = R"sql(
ALTER TABLE patients ADD COLUMN patient_name TEXT NOT NULL DEFAULT '';
CREATE INDEX patients_name_lower ON patients(lower(patient_name));
ALTER TABLE series ADD COLUMN series_number INTEGER NOT NULL DEFAULT 0;
ALTER TABLE series ADD COLUMN description TEXT NOT NULL DEFAULT '';
)sql";

// Version 9: no stored byte unchecked (db/sql/checksum_stored_bytes.h). Surface blobs in version 3,
// with a CRC-32 that every decode checks (a flipped bit in a version 2 blob could decode to a
// plausible mesh and answer with a wrong volume), and a checksum on every cached value; a surface
// blob that is damaged already is left as it is, for soiqd to refuse and soiq-admin verify to list.
// No table changes.
constexpr char kSchemaV9[] = "";

// Version 10: the series' DICOM window (SeriesRecord::window_center/width), where pictures start.
constexpr char kSchemaV10[] = R"sql(
ALTER TABLE series ADD COLUMN window_center REAL NOT NULL DEFAULT 0;
ALTER TABLE series ADD COLUMN window_width REAL NOT NULL DEFAULT 0;
)sql";

// Version 11: the original DICOM instances of image series (InstanceRecord), kept as received so
// that DICOMweb serves them. A file is stored once per sha256 (a re-sent file, an instance of two
// series), like the image blobs; nothing cascades to it, so the writes and deletes remove a file
// when no instance refers to it any more. metadata_crc32 is the CRC-32 of the instance's row (its
// uid, series uid, slice, file and metadata: instance_row_crc32 in db/sql/sql_store.h), checked on
// every read; a file is checked by its sha256. The metadata is JSON of a few kB, so it stays in
// the row; the file, large, in its own table.
constexpr char kSchemaV11[] = R"sql(
CREATE TABLE instance_files (
  sha256 TEXT PRIMARY KEY NOT NULL,
  blob BLOB NOT NULL
);

CREATE TABLE instances (
  sop_instance_uid TEXT PRIMARY KEY NOT NULL,
  series_pk INTEGER NOT NULL REFERENCES series(pk) ON DELETE CASCADE,
  slice INTEGER NOT NULL,
  file_sha256 TEXT NOT NULL REFERENCES instance_files(sha256),
  file_bytes INTEGER NOT NULL,
  metadata TEXT NOT NULL,
  metadata_crc32 INTEGER NOT NULL
);
CREATE INDEX instances_series ON instances(series_pk, slice);
CREATE INDEX instances_file ON instances(file_sha256);
)sql";

// Version 12: where each slice of an unevenly spaced series lies (ImageGeometry::slice_positions_mm,
// db/sql/record_sql.h join_positions); "" for the evenly spaced series every older store holds.
constexpr char kSchemaV12[] = R"sql(
ALTER TABLE series ADD COLUMN slice_positions TEXT NOT NULL DEFAULT '';
)sql";

// Version 13: which features precompute computed for each structure (db::PrecomputedSet): 0, the
// default ones, for every structure an older store holds.
constexpr char kSchemaV13[] = R"sql(
ALTER TABLE stored_features ADD COLUMN precomputed_set INTEGER NOT NULL DEFAULT 0;
)sql";

// Append new steps here; never edit a released one.
const std::vector<Migration>& migrations() {
  static const std::vector<Migration> kMigrations = {
      {1, kSchemaV1},
      {2, kSchemaV2},
      {3, kSchemaV3},
      {4, kSchemaV4, reencode_surface_blobs},
      {5, kSchemaV5, reencode_image_blobs},
      {6, kSchemaV6},
      {7, kSchemaV7},
      {8, kSchemaV8},
      {9, kSchemaV9, sqlite_checksum_stored_bytes},
      {10, kSchemaV10},
      {11, kSchemaV11},
      {12, kSchemaV12},
      {13, kSchemaV13},
  };
  return kMigrations;
}

Status newer_schema(const Connection& c, int version) {
  return failed_precondition("database '" + c.path() + "' has schema version " + std::to_string(version) +
                             ", newer than version " + std::to_string(latest_schema_version()) +
                             " that this soiqd knows; run a newer soiqd");
}

}  // namespace

int latest_schema_version() { return migrations().back().to_version; }

Result<int> schema_version(Connection& c) {
  SOIQ_ASSIGN_OR_RETURN(Statement st, c.prepare("PRAGMA user_version"));
  SOIQ_ASSIGN_OR_RETURN(const bool row, st.step());
  if (!row) return internal_error("PRAGMA user_version returned no row");
  return int(st.int64(0));
}

Status migrate_schema(Connection& c) {
  for (const Migration& m : migrations()) {
    // Read the version inside the write transaction: another process may have migrated meanwhile.
    Status s = run_transaction(c, TransactionKind::kWrite, [&]() -> Status {
      SOIQ_ASSIGN_OR_RETURN(const int version, schema_version(c));
      if (version > latest_schema_version()) return newer_schema(c, version);
      if (version >= m.to_version) return ok_status();
      if (m.sql[0] != '\0') SOIQ_RETURN_IF_ERROR(c.exec(m.sql));
      if (m.run != nullptr) SOIQ_RETURN_IF_ERROR(m.run(c));
      // user_version is part of the database header, so it commits or rolls back with the step.
      return c.exec("PRAGMA user_version = " + std::to_string(m.to_version));
    });
    if (!s.ok()) {
      if (s.code() == StatusCode::kFailedPrecondition) return s;
      return Status(s.code(), "migrating '" + c.path() + "' to schema version " + std::to_string(m.to_version) + ": " +
                                  s.message());
    }
  }
  return ok_status();
}

Status check_schema_readable(Connection& c) {
  SOIQ_ASSIGN_OR_RETURN(const int version, schema_version(c));
  if (version > latest_schema_version()) return newer_schema(c, version);
  if (version == 0) return failed_precondition("database '" + c.path() + "' holds no soiq store (schema version 0)");
  return ok_status();
}

}  // namespace soiq::db
