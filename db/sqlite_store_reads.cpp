// SqliteStore's reads of single records and pages. Each method is one read transaction, so a page
// and its counts come from one snapshot.
#include "db/glob_range.h"
#include "db/page_token.h"
#include "db/sql_conditions.h"
#include "db/sqlite_records.h"
#include "db/sqlite_store.h"
#include "db/validate_records.h"

namespace soiq::db {

Result<PatientRecord> SqliteStore::get_patient(const std::string& patient_id) {
  PatientRecord out;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(
        Statement q, c.prepare(std::string("SELECT ") + kPatientColumns + " FROM patients p WHERE p.patient_id = ?1"));
    q.bind(1, patient_id);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return not_found("patient '" + patient_id + "' not found");
    out = read_patient(q, 0);
    return ok_status();
  }));
  return out;
}

Result<Page<PatientRecord>> SqliteStore::list_patients(const PatientFilter& f, const PageRequest& p) {
  SOIQ_ASSIGN_OR_RETURN(const int size, effective_page_size(p.page_size));
  SOIQ_ASSIGN_OR_RETURN(const std::string after, parse_page_token("patients", p.page_token));
  SOIQ_RETURN_IF_ERROR(validate_patient_filter(f));
  SqlConditions where;
  if (!p.page_token.empty()) where.compare("p.patient_id", ">", after);
  if (!f.patient_id_glob.empty()) where.glob("p.patient_id", f.patient_id_glob);
  if (!f.sex.empty()) where.equal("p.sex", f.sex);
  const std::string sql = std::string("SELECT ") + kPatientColumns + " FROM patients p WHERE 1" + where.sql() +
                          " ORDER BY p.patient_id LIMIT " + std::to_string(size + 1);

  Page<PatientRecord> page;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(sql));
    where.bind(q);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      page.items.push_back(read_patient(q, 0));
    }
    return ok_status();
  }));
  // One row more than the page says whether there is a next page, without a count.
  if (int(page.items.size()) > size) {
    page.items.resize(size);
    page.next_page_token = make_page_token("patients", page.items.back().patient_id);
  }
  return page;
}

Result<StudyRecord> SqliteStore::get_study(const std::string& study_uid) {
  StudyRecord out;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(std::string("SELECT ") + kStudyColumns +
                                                 " FROM studies st JOIN patients p ON p.pk = st.patient_pk "
                                                 "WHERE st.study_uid = ?1"));
    q.bind(1, study_uid);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return not_found("study '" + study_uid + "' not found");
    out = read_study(q, 0);
    return ok_status();
  }));
  return out;
}

Result<Page<StudyRecord>> SqliteStore::list_studies(const std::string& patient_id, const PageRequest& p) {
  SOIQ_ASSIGN_OR_RETURN(const int size, effective_page_size(p.page_size));
  SOIQ_ASSIGN_OR_RETURN(const std::string after, parse_page_token("studies", p.page_token));
  Page<StudyRecord> page;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    {
      SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare("SELECT 1 FROM patients WHERE patient_id = ?1"));
      q.bind(1, patient_id);
      SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
      if (!found) return not_found("patient '" + patient_id + "' not found");
    }
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(std::string("SELECT ") + kStudyColumns +
                                                 " FROM studies st JOIN patients p ON p.pk = st.patient_pk "
                                                 "WHERE p.patient_id = ?1 AND st.study_uid > ?2 "
                                                 "ORDER BY st.study_uid LIMIT ?3"));
    q.bind(1, patient_id);
    q.bind(2, after);  // "" sorts before every uid
    q.bind(3, int64_t{size} + 1);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      page.items.push_back(read_study(q, 0));
    }
    return ok_status();
  }));
  if (int(page.items.size()) > size) {
    page.items.resize(size);
    page.next_page_token = make_page_token("studies", page.items.back().study_uid);
  }
  return page;
}

Result<std::vector<SeriesRecord>> SqliteStore::list_series(const std::string& study_uid) {
  std::vector<SeriesRecord> out;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    {
      SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare("SELECT 1 FROM studies WHERE study_uid = ?1"));
      q.bind(1, study_uid);
      SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
      if (!found) return not_found("study '" + study_uid + "' not found");
    }
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(std::string("SELECT ") + kSeriesColumns +
                                                 " FROM series se JOIN studies st ON st.pk = se.study_pk "
                                                 "WHERE st.study_uid = ?1 ORDER BY se.series_uid"));
    q.bind(1, study_uid);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      out.push_back(read_series(q, 0));
    }
    return ok_status();
  }));
  return out;
}

Result<SeriesRecord> SqliteStore::get_series(const std::string& series_uid) {
  SeriesRecord out;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(std::string("SELECT ") + kSeriesColumns +
                                                 " FROM series se JOIN studies st ON st.pk = se.study_pk "
                                                 "WHERE se.series_uid = ?1"));
    q.bind(1, series_uid);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return not_found("series '" + series_uid + "' not found");
    out = read_series(q, 0);
    return ok_status();
  }));
  return out;
}

Result<std::string> SqliteStore::get_image_blob(const std::string& series_uid) {
  std::string out;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare("SELECT b.blob FROM series se JOIN image_blobs b ON b.sha256 = "
                                                 "se.image_sha256 WHERE se.series_uid = ?1"));
    q.bind(1, series_uid);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return not_found("series '" + series_uid + "' not found");
    out = q.blob(0);
    return ok_status();
  }));
  return out;
}

Result<StructureRecord> SqliteStore::get_structure(int64_t id) {
  StructureRecord out;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(std::string("SELECT ") + kStructureColumns + " FROM " +
                                                 kStructureJoin + " WHERE s.id = ?1"));
    q.bind(1, id);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return not_found("structure " + std::to_string(id) + " not found");
    out = read_structure(q, 0);
    return ok_status();
  }));
  return out;
}

Result<Page<StructureRecord>> SqliteStore::list_structures(const StructureFilter& f, const PageRequest& p) {
  SOIQ_ASSIGN_OR_RETURN(const int size, effective_page_size(p.page_size));
  SOIQ_ASSIGN_OR_RETURN(const std::string after, parse_page_token("structures", p.page_token));
  SOIQ_RETURN_IF_ERROR(validate_structure_filter(f));
  int64_t after_id = 0;
  if (!after.empty()) {
    size_t used = 0;
    try {
      after_id = std::stoll(after, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != after.size()) return invalid_argument("page_token does not hold a structure id");
  }
  std::string sql = std::string("SELECT ") + kStructureColumns + " FROM " + kStructureJoin + " WHERE s.id > " +
                    std::to_string(after_id);
  SqlConditions where;
  if (!f.patient_id.empty()) where.equal("p.patient_id", f.patient_id);
  if (!f.study_uid.empty()) where.equal("st.study_uid", f.study_uid);
  if (!f.name_glob.empty()) where.glob("lower(s.name)", ascii_lower(f.name_glob));
  if (!f.laterality.empty()) where.equal("s.laterality", f.laterality);
  sql += where.sql() + " ORDER BY s.id LIMIT " + std::to_string(size + 1);

  Page<StructureRecord> page;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(sql));
    where.bind(q);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      page.items.push_back(read_structure(q, 0));
    }
    return ok_status();
  }));
  if (int(page.items.size()) > size) {
    page.items.resize(size);
    page.next_page_token = make_page_token("structures", std::to_string(page.items.back().id));
  }
  return page;
}

Result<std::string> SqliteStore::get_surface_blob(const std::string& sha256) {
  std::string out;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare("SELECT blob FROM surfaces WHERE sha256 = ?1"));
    q.bind(1, sha256);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return not_found("surface " + sha256 + " not found");
    out = q.blob(0);
    return ok_status();
  }));
  return out;
}

}  // namespace soiq::db
