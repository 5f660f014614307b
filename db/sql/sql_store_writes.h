#pragma once
// Internal to db/sql/sql_store_*.cpp, not part of the store's interface: the steps SqlStore's
// writes are made of, shared between the files that hold the writes of each record kind. Each
// step runs inside the caller's write transaction (SqlStore::write) and leaves committing or
// rolling back to it; inputs are validated before the transaction starts.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/status.h"
#include "db/sql/sql_session.h"
#include "db/store.h"

namespace soiq::db {

// The keys of a study and of its patient, as upsert_patient_and_study leaves them.
struct StudyKeys {
  int64_t patient_pk = 0;
  int64_t study_pk = 0;
};

// sql_store_patients.cpp: inserts or updates the patient and the study (non-empty given fields
// overwrite), and keeps the computed ages of the patient's studies in step with the dates.
// FAILED_PRECONDITION when the study belongs to another patient.
Result<StudyKeys> upsert_patient_and_study(SqlSession& c, const PatientRecord& patient, const StudyRecord& study);

// sql_store_structures.cpp: the writes of a structure (the patient and study, the surface blob,
// then a new, replaced or recognised structure), checked before by validate_new_structure.
Result<AddedStructure> insert_structure(SqlSession& c, const NewStructure& s);

// sql_store_series.cpp: the writes of a series (the patient and study, the image blob, the
// series), checked before by validate_new_series. Returns true when a series with the same uid was
// replaced.
Result<bool> insert_series(SqlSession& c, const NewSeries& s);

// sql_store_instances.cpp: the instances of a series (NewSeries::instances), checked before by
// validate_new_series, written after the series' row. add_instances stores those the series lacks
// (one it holds is kept; its file, or its row, is repaired when damaged); replace_instances first
// deletes the series' stored ones and, after adding, the files no instance refers to any more.
// FAILED_PRECONDITION for an instance stored in another series.
Status add_instances(SqlSession& c, const NewSeries& s);
Status replace_instances(SqlSession& c, const NewSeries& s);

// sql_store_stage1_rows.cpp: rewrites the stage-1 rows of every structure of the patient.
Status refresh_stage1_rows(SqlSession& c, int64_t patient_pk);

// sql_store_precompute.cpp: queue a structure for precompute (again: a failure is forgotten);
// with `surface_changed`, its stored values go too (refresh its stage-1 rows after). And every
// structure of a study, which gained or changed an image (their intensities are to compute).
Status queue_precompute(SqlSession& c, int64_t structure_id, bool surface_changed);
Status queue_precompute_of_study(SqlSession& c, int64_t study_pk);

// sql_store_cache.cpp: whether the surface is stored.
Result<bool> surface_exists(SqlSession& c, const std::string& sha256);

// sql_store_blobs.cpp: the blob stored under `sha256` in `table` (surfaces or image_blobs), if
// any, compared with `blob` and replaced by it when they differ (a damaged blob, or one of an older
// version: `blob` was just encoded from what its sha256 names). kAbsent: the caller inserts it.
enum class StoredBlob { kAbsent, kSame, kReplaced };
Result<StoredBlob> replace_differing_blob(SqlSession& c, std::string_view table, const std::string& sha256,
                                          std::string_view blob);

// sql_store_deletes.cpp: delete the blob when nothing refers to it any more (a surface takes
// its cached features with it).
Status delete_surface_if_orphan(SqlSession& c, const std::string& sha256);
Status delete_image_if_orphan(SqlSession& c, const std::string& sha256);
Status delete_instance_file_if_orphan(SqlSession& c, const std::string& sha256);

// sql_store_copy.cpp: whether the store has `table`. A store opened read only is not migrated, so
// the tables of later schema versions (instances, instance_files) may be missing from it: the
// reads that run on such a store (soiq-admin verify's scan and digests) read them as empty.
Result<bool> table_exists(SqlSession& c, const std::string& table);
// Likewise for a column a later version added to an older table (series.slice_positions).
Result<bool> column_exists(SqlSession& c, const std::string& table, const std::string& column);

}  // namespace soiq::db
