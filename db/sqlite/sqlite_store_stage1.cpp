// SqliteStore::stage1: the structured half of a query (DESIGN.md "Queries") as one SQL query over
// indexed columns.
#include <map>

#include "db/sql/record_sql.h"
#include "db/sql/stage1_sql.h"
#include "db/sqlite/sqlite_store.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

// One candidate's structure by id, after SELECT and its column lists, with the keys of its study
// and patient; then those by key.
constexpr char kCandidateByIdSql[] = R"sql(
  WHERE s.id = ?1)sql";
constexpr char kStudyAndPatientKeyColumns[] = R"sql(
  st.pk, p.pk)sql";
constexpr char kPatientByKeySql[] = R"sql(
  FROM patients p
  WHERE p.pk = ?1)sql";
constexpr char kStudyByKeySql[] = R"sql(
  FROM studies st
  JOIN patients p ON p.pk = st.patient_pk
  WHERE st.pk = ?1)sql";

}  // namespace

Result<std::vector<std::string>> SqliteStore::stage1_plan(const Stage1Filter& f, int64_t limit) {
  SOIQ_RETURN_IF_ERROR(validate_stage1_filter(f));
  const SqlConditions where = stage1_conditions(f, SqlDialect::kSqlite);
  std::vector<std::string> plan;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare("EXPLAIN QUERY PLAN " + stage1_ids_sql(where, f, limit + 1)));
    where.bind(q);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      plan.push_back(q.text(3));
    }
    return ok_status();
  }));
  return plan;
}

Result<std::vector<Candidate>> SqliteStore::stage1(const Stage1Filter& f, int64_t limit) {
  if (limit < 1) return invalid_argument("stage-1 limit must be >= 1, got " + std::to_string(limit));
  SOIQ_RETURN_IF_ERROR(validate_stage1_filter(f));
  const SqlConditions where = stage1_conditions(f, SqlDialect::kSqlite);
  std::vector<Candidate> out;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    // The matching ids from stage1_rows alone, at most limit + 1 of them: the filters choose the
    // plan on that one narrow table, and no record is built before we know there are not too many.
    // With twins, each hit's twin id comes from the same query (a self-join of structures).
    std::vector<std::pair<int64_t, std::optional<int64_t>>> ids;
    {
      SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(stage1_ids_sql(where, f, limit + 1)));
      where.bind(q);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        ids.emplace_back(q.int64(0), q.is_null(1) ? std::nullopt : std::optional<int64_t>(q.int64(1)));
      }
    }
    if (int64_t(ids.size()) > limit) {
      // Only for the message: the full count, in the same snapshot.
      SOIQ_ASSIGN_OR_RETURN(Statement all, c.prepare(stage1_count_sql(where)));
      where.bind(all);
      SOIQ_ASSIGN_OR_RETURN(const bool counted, all.step());
      const int64_t total = counted ? all.int64(0) : limit + 1;
      return resource_exhausted("stage 1 matches " + std::to_string(total) + " structures, more than the limit of " +
                                std::to_string(limit) + "; narrow the stage-1 filter");
    }
    // Then each record by key: the structure (a few index probes), and its patient and study once
    // per query however many of their structures it keeps (each has count subqueries).
    SOIQ_ASSIGN_OR_RETURN(Statement structure, c.prepare(select_sql({kStructureColumns, kStudyAndPatientKeyColumns},
                                                                    {kStructureFrom, kCandidateByIdSql})));
    SOIQ_ASSIGN_OR_RETURN(Statement patient, c.prepare(select_sql({kPatientColumns}, {kPatientByKeySql})));
    SOIQ_ASSIGN_OR_RETURN(Statement study, c.prepare(select_sql({kStudyColumns}, {kStudyByKeySql})));
    std::map<int64_t, PatientRecord> patients;
    std::map<int64_t, StudyRecord> studies;
    auto read_one = [](Statement& q, int64_t key, const std::string& what) -> Status {
      q.reset();
      q.bind(1, key);
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) return internal_error(what + " vanished in a read");
      return ok_status();
    };
    out.reserve(ids.size());
    for (const auto& [id, twin_id] : ids) {
      SOIQ_RETURN_IF_ERROR(read_one(structure, id, "structure " + std::to_string(id)));
      Candidate cand;
      cand.structure = read_structure(structure, 0);
      const int64_t study_pk = structure.int64(kStructureColumnCount);
      const int64_t patient_pk = structure.int64(kStructureColumnCount + 1);
      auto p = patients.find(patient_pk);
      if (p == patients.end()) {
        SOIQ_RETURN_IF_ERROR(read_one(patient, patient_pk, "the patient of structure " + std::to_string(id)));
        p = patients.emplace(patient_pk, read_patient(patient, 0)).first;
      }
      auto st = studies.find(study_pk);
      if (st == studies.end()) {
        SOIQ_RETURN_IF_ERROR(read_one(study, study_pk, "the study of structure " + std::to_string(id)));
        st = studies.emplace(study_pk, read_study(study, 0)).first;
      }
      cand.patient = p->second;
      cand.study = st->second;
      if (twin_id) {
        SOIQ_RETURN_IF_ERROR(read_one(structure, *twin_id, "twin structure " + std::to_string(*twin_id)));
        cand.twin = read_structure(structure, 0);
      }
      out.push_back(std::move(cand));
    }
    return ok_status();
  }));
  return out;
}

}  // namespace soiq::db
