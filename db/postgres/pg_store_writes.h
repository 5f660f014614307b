#pragma once
// Internal to db/postgres/pg_store_*.cpp, not part of the store's interface: the steps PgStore's
// writes are made of, as sqlite_store_writes.h has them for SQLite. Each step runs inside the
// caller's write transaction (PgStore::write) and leaves committing or rolling back to it; inputs
// are validated (validate_records.h) before the transaction starts.

#include <cstdint>
#include <string>

#include "core/base/status.h"
#include "db/postgres/pg_connection.h"
#include "db/store.h"

namespace soiq::db {

struct PgStudyKeys {
  int64_t patient_pk = 0;
  int64_t study_pk = 0;
};

// pg_store_patients.cpp: inserts or updates the patient and the study (record_merge.h), and keeps
// the computed ages of the patient's studies in step with the dates. FAILED_PRECONDITION when the
// study belongs to another patient.
Result<PgStudyKeys> pg_upsert_patient_and_study(PgConnection& c, const PatientRecord& patient,
                                                const StudyRecord& study);

// pg_store_structures.cpp: a new, replaced or recognised structure with its surface blob.
Result<AddedStructure> pg_insert_structure(PgConnection& c, const NewStructure& s);
// pg_store_series.cpp: the series and its image blob; true when a series with its uid was replaced.
Result<bool> pg_insert_series(PgConnection& c, const NewSeries& s);

// pg_store_stage1_rows.cpp: rewrites the stage-1 rows of every structure of the patient.
Status pg_refresh_stage1_rows(PgConnection& c, int64_t patient_pk);

// pg_store_precompute.cpp: queue a structure for precompute (again: a failure is forgotten); with
// `surface_changed` its stored values go too. And every structure of a study that gained or
// changed an image.
Status pg_queue_precompute(PgConnection& c, int64_t structure_id, bool surface_changed);
Status pg_queue_precompute_of_study(PgConnection& c, int64_t study_pk);

// pg_store_deletes.cpp: delete the blob when nothing refers to it any more (a surface takes its
// cached features with it).
Status pg_delete_surface_if_orphan(PgConnection& c, const std::string& sha256);
Status pg_delete_image_if_orphan(PgConnection& c, const std::string& sha256);

}  // namespace soiq::db
