// SqlStore's deletes: a structure, or a patient with everything of it. Blobs and cached
// features nothing refers to any more go in the same transaction, so the file never keeps data
// of a deleted patient.

#include <set>
#include <string>

#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"

namespace soiq::db {
namespace {

// A blob's DELETE whose only parameter is its sha256.
Status delete_by_sha256(SqlSession& c, const char* sql, const std::string& sha256) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement del, c.prepare(sql));
  del.bind(1, sha256);
  return del.run();
}

constexpr char kDeleteOrphanSurfaceSql[] = R"sql(
  DELETE FROM surfaces
  WHERE sha256 = ?1 AND NOT EXISTS (SELECT 1 FROM structures WHERE surface_sha256 = ?1))sql";

}  // namespace

// Deletes the surface (and, by cascade, its cached features) when no structure refers to it.
Status delete_surface_if_orphan(SqlSession& c, const std::string& sha256) {
  return delete_by_sha256(c, kDeleteOrphanSurfaceSql, sha256);
}

namespace {

constexpr char kDeleteOrphanImageSql[] = R"sql(
  DELETE FROM image_blobs
  WHERE sha256 = ?1 AND NOT EXISTS (SELECT 1 FROM series WHERE image_sha256 = ?1))sql";

}  // namespace

Status delete_image_if_orphan(SqlSession& c, const std::string& sha256) {
  return delete_by_sha256(c, kDeleteOrphanImageSql, sha256);
}

namespace {

constexpr char kDeleteOrphanInstanceFileSql[] = R"sql(
  DELETE FROM instance_files
  WHERE sha256 = ?1 AND NOT EXISTS (SELECT 1 FROM instances WHERE file_sha256 = ?1))sql";

}  // namespace

Status delete_instance_file_if_orphan(SqlSession& c, const std::string& sha256) {
  return delete_by_sha256(c, kDeleteOrphanInstanceFileSql, sha256);
}

namespace {

constexpr char kDeleteStructureSql[] = R"sql(
  DELETE FROM structures WHERE id = ?1
  RETURNING surface_sha256)sql";

}  // namespace

Result<int64_t> SqlStore::remove_structure(int64_t id) {
  SOIQ_RETURN_IF_ERROR(write([&](SqlSession& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement del, c.prepare(kDeleteStructureSql));
    del.bind(1, id);
    SOIQ_ASSIGN_OR_RETURN(const bool row, del.step());
    if (!row) return not_found("structure " + std::to_string(id) + " not found");
    const std::string sha = del.text(0);
    SOIQ_RETURN_IF_ERROR(del.run());
    return delete_surface_if_orphan(c, sha);
  }));
  return int64_t{1};
}

namespace {

constexpr char kSurfacesOfPatientSql[] = R"sql(
  SELECT s.surface_sha256
  FROM structures s
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE p.patient_id = ?1)sql";

constexpr char kImagesOfPatientSql[] = R"sql(
  SELECT se.image_sha256
  FROM series se
  JOIN studies st ON st.pk = se.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE p.patient_id = ?1)sql";

constexpr char kInstanceFilesOfPatientSql[] = R"sql(
  SELECT i.file_sha256
  FROM instances i
  JOIN series se ON se.pk = i.series_pk
  JOIN studies st ON st.pk = se.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE p.patient_id = ?1)sql";

// ON DELETE CASCADE takes the studies, their series (and their instances) and structures.
constexpr char kDeletePatientSql[] = R"sql(
  DELETE FROM patients WHERE patient_id = ?1)sql";

// The blobs a patient refers to, by sha256, collected before the cascade removes the references;
// `rows`: how many rows referred to them.
struct Collected {
  std::set<std::string> shas;
  int64_t rows = 0;
};

Result<Collected> collect_of_patient(SqlSession& c, const char* sql, const std::string& patient_id) {
  Collected out;
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(sql));
  q.bind(1, patient_id);
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return out;
    ++out.rows;
    out.shas.insert(q.text(0));
  }
}

}  // namespace

Result<int64_t> SqlStore::remove_patient(const std::string& patient_id) {
  int64_t deleted = 0;
  SOIQ_RETURN_IF_ERROR(write([&](SqlSession& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(const Collected surfaces, collect_of_patient(c, kSurfacesOfPatientSql, patient_id));
    SOIQ_ASSIGN_OR_RETURN(const Collected images, collect_of_patient(c, kImagesOfPatientSql, patient_id));
    SOIQ_ASSIGN_OR_RETURN(const Collected files, collect_of_patient(c, kInstanceFilesOfPatientSql, patient_id));
    deleted = surfaces.rows;  // one row per structure
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement del, c.prepare(kDeletePatientSql));
      del.bind(1, patient_id);
      SOIQ_RETURN_IF_ERROR(del.run());
      if (del.changes() == 0) return not_found("patient '" + patient_id + "' not found");
    }
    for (const std::string& sha : surfaces.shas) SOIQ_RETURN_IF_ERROR(delete_surface_if_orphan(c, sha));
    for (const std::string& sha : images.shas) SOIQ_RETURN_IF_ERROR(delete_image_if_orphan(c, sha));
    for (const std::string& sha : files.shas) SOIQ_RETURN_IF_ERROR(delete_instance_file_if_orphan(c, sha));
    return ok_status();
  }));
  return deleted;
}

}  // namespace soiq::db
