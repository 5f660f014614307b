// SqlStore's deletes: a structure, or a patient with everything of it. Blobs and cached
// features nothing refers to any more go in the same transaction, so the file never keeps data
// of a deleted patient.

#include <set>
#include <string>

#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"

namespace soiq::db {
namespace {

constexpr char kDeleteOrphanSurfaceSql[] = R"sql(
  DELETE FROM surfaces
  WHERE sha256 = ?1 AND NOT EXISTS (SELECT 1 FROM structures WHERE surface_sha256 = ?1))sql";

}  // namespace

// Deletes the surface (and, by cascade, its cached features) when no structure refers to it.
Status delete_surface_if_orphan(SqlSession& c, const std::string& sha256) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement del, c.prepare(kDeleteOrphanSurfaceSql));
  del.bind(1, sha256);
  return del.run();
}

namespace {

constexpr char kDeleteOrphanImageSql[] = R"sql(
  DELETE FROM image_blobs
  WHERE sha256 = ?1 AND NOT EXISTS (SELECT 1 FROM series WHERE image_sha256 = ?1))sql";

}  // namespace

Status delete_image_if_orphan(SqlSession& c, const std::string& sha256) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement del, c.prepare(kDeleteOrphanImageSql));
  del.bind(1, sha256);
  return del.run();
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

// ON DELETE CASCADE takes the studies, their series and structures.
constexpr char kDeletePatientSql[] = R"sql(
  DELETE FROM patients WHERE patient_id = ?1)sql";

}  // namespace

Result<int64_t> SqlStore::remove_patient(const std::string& patient_id) {
  int64_t deleted = 0;
  SOIQ_RETURN_IF_ERROR(write([&](SqlSession& c) -> Status {
    // The blobs the patient refers to, collected before the cascade removes the references.
    std::set<std::string> surfaces, images;
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kSurfacesOfPatientSql));
      q.bind(1, patient_id);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        ++deleted;
        surfaces.insert(q.text(0));
      }
    }
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kImagesOfPatientSql));
      q.bind(1, patient_id);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        images.insert(q.text(0));
      }
    }
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement del, c.prepare(kDeletePatientSql));
      del.bind(1, patient_id);
      SOIQ_RETURN_IF_ERROR(del.run());
      if (del.changes() == 0) return not_found("patient '" + patient_id + "' not found");
    }
    for (const std::string& sha : surfaces) SOIQ_RETURN_IF_ERROR(delete_surface_if_orphan(c, sha));
    for (const std::string& sha : images) SOIQ_RETURN_IF_ERROR(delete_image_if_orphan(c, sha));
    return ok_status();
  }));
  return deleted;
}

}  // namespace soiq::db
