// SqlStore's reads of single records and pages. Each method is one read transaction, so a page
// and its counts come from one snapshot.
#include <algorithm>

#include "db/page_token.h"
#include "db/sql/glob_range.h"
#include "db/sql/keyed_rows.h"
#include "db/sql/record_sql.h"
#include "db/sql/sql_conditions.h"
#include "db/sql/sql_store.h"
#include "db/validate_records.h"

namespace soiq::db {

template <typename T, typename Key, typename Make>
Result<T> SqlStore::one_row(const char* sql, const Key& key, const Make& make, const std::string& missing) {
  T out;
  SOIQ_RETURN_IF_ERROR(read_one([&](SqlSession& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(sql));
    q.bind(1, key);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return not_found(missing);
    out = make(q);
    return ok_status();
  }));
  return out;
}

namespace {

constexpr char kPatientByIdSql[] = R"sql(
  FROM patients p
  WHERE p.patient_id = ?1)sql";

}  // namespace

Result<PatientRecord> SqlStore::get_patient(const std::string& patient_id) {
  static const std::string sql = select_sql({kPatientColumns}, {kPatientByIdSql});
  return one_row<PatientRecord>(
      sql.c_str(), patient_id, [](SqlStatement& q) { return read_patient(q, 0); },
      "patient '" + patient_id + "' not found");
}

namespace {

// A page of patients: the filter's conditions (" AND …") go between these two, the page size + 1
// after them.
constexpr char kPatientPageFromSql[] = R"sql(
  FROM patients p
  WHERE true)sql";
constexpr char kPatientPageOrderSql[] = R"sql(
  ORDER BY p.patient_id
  LIMIT)sql";

}  // namespace

Result<Page<PatientRecord>> SqlStore::list_patients(const PatientFilter& f, const PageRequest& p) {
  SOIQ_ASSIGN_OR_RETURN(const int size, effective_page_size(p.page_size));
  SOIQ_ASSIGN_OR_RETURN(const std::string after, parse_page_token("patients", p.page_token));
  SOIQ_RETURN_IF_ERROR(validate_patient_filter(f));
  Page<PatientRecord> page;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    page.items.clear();
    SqlConditions where(c.dialect());
    if (!p.page_token.empty()) where.compare("p.patient_id", ">", after);
    if (!f.patient_id_glob.empty()) where.glob("p.patient_id", f.patient_id_glob);
    if (!f.sex.empty()) where.equal("p.sex", f.sex);
    SOIQ_ASSIGN_OR_RETURN(
        SqlStatement q, c.prepare(select_sql({kPatientColumns}, {kPatientPageFromSql, where.sql(), kPatientPageOrderSql,
                                                                 std::to_string(size + 1)})));
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

namespace {

constexpr char kStudyByUidSql[] = R"sql(
  FROM studies st
  JOIN patients p ON p.pk = st.patient_pk
  WHERE st.study_uid = ?1)sql";

}  // namespace

Result<StudyRecord> SqlStore::get_study(const std::string& study_uid) {
  static const std::string sql = select_sql({kStudyColumns}, {kStudyByUidSql});
  return one_row<StudyRecord>(
      sql.c_str(), study_uid, [](SqlStatement& q) { return read_study(q, 0); }, "study '" + study_uid + "' not found");
}

namespace {

constexpr char kPatientExistsSql[] = R"sql(
  SELECT 1 FROM patients WHERE patient_id = ?1)sql";

constexpr char kStudyPageSql[] = R"sql(
  FROM studies st
  JOIN patients p ON p.pk = st.patient_pk
  WHERE p.patient_id = ?1 AND st.study_uid > ?2
  ORDER BY st.study_uid
  LIMIT ?3)sql";

}  // namespace

Result<Page<StudyRecord>> SqlStore::list_studies(const std::string& patient_id, const PageRequest& p) {
  SOIQ_ASSIGN_OR_RETURN(const int size, effective_page_size(p.page_size));
  SOIQ_ASSIGN_OR_RETURN(const std::string after, parse_page_token("studies", p.page_token));
  Page<StudyRecord> page;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kPatientExistsSql));
      q.bind(1, patient_id);
      SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
      if (!found) return not_found("patient '" + patient_id + "' not found");
    }
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(select_sql({kStudyColumns}, {kStudyPageSql})));
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

namespace {

constexpr char kStudyExistsSql[] = R"sql(
  SELECT 1 FROM studies WHERE study_uid = ?1)sql";

constexpr char kSeriesOfStudySql[] = R"sql(
  FROM series se
  JOIN studies st ON st.pk = se.study_pk
  WHERE st.study_uid = ?1
  ORDER BY se.series_uid)sql";

}  // namespace

Result<std::vector<SeriesRecord>> SqlStore::list_series(const std::string& study_uid) {
  std::vector<SeriesRecord> out;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kStudyExistsSql));
      q.bind(1, study_uid);
      SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
      if (!found) return not_found("study '" + study_uid + "' not found");
    }
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(select_sql({kSeriesColumns}, {kSeriesOfStudySql})));
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

namespace {

// Every study of the IN list (its parameters between the two parts) with its series, if any.
constexpr char kSeriesOfStudiesSql[] = R"sql(
  FROM studies st
  LEFT JOIN series se ON se.study_pk = st.pk
  WHERE st.study_uid)sql";
constexpr char kSeriesOfStudiesOrderSql[] = R"sql(
  ORDER BY st.study_uid, se.series_uid)sql";

}  // namespace

Result<std::map<std::string, std::vector<SeriesRecord>>> SqlStore::series_of_studies(
    const std::vector<std::string>& uids) {
  std::map<std::string, std::vector<SeriesRecord>> out;
  // Each study once: one named in two statements would have its series twice.
  std::vector<std::string> study_uids = uids;
  std::sort(study_uids.begin(), study_uids.end());
  study_uids.erase(std::unique(study_uids.begin(), study_uids.end()), study_uids.end());
  if (study_uids.empty()) return out;
  // read_one: on PostgreSQL every key goes in one statement (keyed_rows.h), which needs no BEGIN and
  // COMMIT of its own (two round trips of a warm query); SQLite's read_one is a transaction.
  SOIQ_RETURN_IF_ERROR(read_one([&](SqlSession& c) -> Status {
    out.clear();
    static const std::string sql = select_sql({"st.study_uid", kSeriesColumns}, {kSeriesOfStudiesSql});
    return for_each_keyed_row(c, study_uids, KeyedSql{sql, kSeriesOfStudiesOrderSql}, [&](const SqlStatement& q) {
      std::vector<SeriesRecord>& series = out[q.text(0)];
      if (!q.is_null(1)) series.push_back(read_series(q, 1));  // NULL: a study without series
    });
  }));
  return out;
}

namespace {

constexpr char kSeriesByUidSql[] = R"sql(
  FROM series se
  JOIN studies st ON st.pk = se.study_pk
  WHERE se.series_uid = ?1)sql";

}  // namespace

Result<SeriesRecord> SqlStore::get_series(const std::string& series_uid) {
  static const std::string sql = select_sql({kSeriesColumns}, {kSeriesByUidSql});
  return one_row<SeriesRecord>(
      sql.c_str(), series_uid, [](SqlStatement& q) { return read_series(q, 0); },
      "series '" + series_uid + "' not found");
}

namespace {

constexpr char kImageBlobOfSeriesSql[] = R"sql(
  SELECT b.blob
  FROM series se
  JOIN image_blobs b ON b.sha256 = se.image_sha256
  WHERE se.series_uid = ?1)sql";

}  // namespace

Result<std::string> SqlStore::image_blob(const std::string& series_uid) {
  return one_row<std::string>(
      kImageBlobOfSeriesSql, series_uid, [](SqlStatement& q) { return q.blob(0); },
      "series '" + series_uid + "' not found");
}

namespace {

constexpr char kStructureByIdSql[] = R"sql(
  WHERE s.id = ?1)sql";

}  // namespace

Result<StructureRecord> SqlStore::get_structure(int64_t id) {
  static const std::string sql = select_sql({kStructureColumns}, {kStructureFrom, kStructureByIdSql});
  return one_row<StructureRecord>(
      sql.c_str(), id, [](SqlStatement& q) { return read_structure(q, 0); },
      "structure " + std::to_string(id) + " not found");
}

namespace {

// A page of structures: the last id of the previous page follows the first, the filter's
// conditions (" AND …") come next, then the second and the page size + 1.
constexpr char kStructurePageWhereSql[] = R"sql(
  WHERE s.id >)sql";
constexpr char kStructurePageOrderSql[] = R"sql(
  ORDER BY s.id
  LIMIT)sql";

}  // namespace

Result<Page<StructureRecord>> SqlStore::list_structures(const StructureFilter& f, const PageRequest& p) {
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
  Page<StructureRecord> page;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    page.items.clear();
    SqlConditions where(c.dialect());
    if (f.patient_id.find_first_of("*?[") != std::string::npos) {
      where.glob("p.patient_id", f.patient_id);
    } else if (!f.patient_id.empty()) {
      where.equal("p.patient_id", f.patient_id);
    }
    if (!f.study_uid.empty()) where.equal("st.study_uid", f.study_uid);
    if (!f.name_glob.empty()) where.glob("lower(s.name)", ascii_lower(f.name_glob));
    if (!f.laterality.empty()) where.equal("s.laterality", f.laterality);
    const std::string sql =
        select_sql({kStructureColumns}, {kStructureFrom, kStructurePageWhereSql, std::to_string(after_id), where.sql(),
                                         kStructurePageOrderSql, std::to_string(size + 1)});
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(sql));
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

namespace {

constexpr char kSurfaceBlobSql[] = R"sql(
  SELECT blob FROM surfaces WHERE sha256 = ?1)sql";

}  // namespace

Result<std::string> SqlStore::surface_blob(const std::string& sha256) {
  return one_row<std::string>(
      kSurfaceBlobSql, sha256, [](SqlStatement& q) { return q.blob(0); }, "surface " + sha256 + " not found");
}

}  // namespace soiq::db
