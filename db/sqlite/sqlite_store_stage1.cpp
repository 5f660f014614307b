// SqliteStore::stage1: the structured half of a query (DESIGN.md "Queries") as one SQL query over
// indexed columns.
#include <map>

#include "db/sqlite/glob_range.h"
#include "db/sqlite/sql_conditions.h"
#include "db/sqlite/sqlite_records.h"
#include "db/sqlite/sqlite_store.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

// A hit's contralateral twin: same study, same name in ASCII lower case (SQLite's lower(), as
// stage1_rows.name_lower), the other laterality; the lowest id when a study has several.
constexpr char kTwinIdColumn[] = R"sql(
  (SELECT t.id FROM structures s JOIN structures t
     ON t.study_pk = s.study_pk AND lower(t.name) = lower(s.name)
    AND t.laterality = CASE s.laterality WHEN 'L' THEN 'R' WHEN 'R' THEN 'L' END
   WHERE s.id = r.structure_id ORDER BY t.id LIMIT 1))sql";
constexpr char kNoTwinIdColumn[] = R"sql( NULL)sql";

// The stage-1 rows the filter keeps: its conditions (" AND …", stage1_conditions) follow.
constexpr char kStage1RowsSql[] = R"sql(
  FROM stage1_rows r
  WHERE 1)sql";

// The ids of the rows, each with its twin's id or NULL, at most `limit` of them.
constexpr char kStage1IdsSql[] = R"sql(
  SELECT r.structure_id,)sql";
constexpr char kStage1IdsOrderSql[] = R"sql(
  ORDER BY r.structure_id
  LIMIT )sql";
// With conditions on stored features: "+" keeps SQLite from scanning the whole table in id order
// (to spare a sort) where the searches of the unstored rows' partial index and of a feature's index
// read only the rows that can match; the few it finds are then sorted.
constexpr char kStage1IdsOrderUnindexedSql[] = R"sql(
  ORDER BY +r.structure_id
  LIMIT )sql";

std::string stage1_ids_sql(const SqlConditions& where, const Stage1Filter& f, int64_t limit) {
  return std::string(kStage1IdsSql) + (f.twins ? kTwinIdColumn : kNoTwinIdColumn) + kStage1RowsSql + where.sql() +
         (f.stored_features.empty() ? kStage1IdsOrderSql : kStage1IdsOrderUnindexedSql) + std::to_string(limit);
}

constexpr char kStage1CountSql[] = R"sql(
  SELECT count(*))sql";

std::string stage1_count_sql(const SqlConditions& where) {
  return std::string(kStage1CountSql) + kStage1RowsSql + where.sql();
}

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

// Every condition is on stage1_rows (alias r), so the query reads one narrow table and joins the
// records only for the rows it returns.
SqlConditions stage1_conditions(const Stage1Filter& f) {
  SqlConditions where;
  if (!f.patient_id_glob.empty()) where.glob("r.patient_id", f.patient_id_glob);
  if (!f.sex.empty()) where.equal("r.sex", f.sex);
  // An unknown date ('') or age (NULL) never satisfies a range: `> ''` keeps the range an index
  // range where only an upper bound is given.
  if (!f.birth_date_from.empty()) where.compare("r.birth_date", ">=", f.birth_date_from);
  if (!f.birth_date_to.empty()) {
    where.compare("r.birth_date", "<=", f.birth_date_to);
    if (f.birth_date_from.empty()) where.compare("r.birth_date", ">", std::string());
  }
  if (f.min_age_years) where.compare("r.age_years", ">=", *f.min_age_years);
  if (f.max_age_years) where.compare("r.age_years", "<=", *f.max_age_years);
  if (!f.study_date_from.empty()) where.compare("r.study_date", ">=", f.study_date_from);
  if (!f.study_date_to.empty()) {
    where.compare("r.study_date", "<=", f.study_date_to);
    if (f.study_date_from.empty()) where.compare("r.study_date", ">", std::string());
  }
  // The study's modality or any of its series', all in r.modalities as /MR/CT/. Sex, laterality and
  // modality have no index on purpose: each keeps a third of the rows or more, where reading the
  // narrow table beats an index search, and an index would tempt SQLite (which has no statistics
  // here) to drive the query by it rather than by a selective range.
  if (!f.modality.empty()) where.with_parameter("instr(r.modalities, '/' || ? || '/') > 0", f.modality);
  if (!f.study_description_glob.empty()) where.glob("r.description", f.study_description_glob);
  if (!f.structure_name_glob.empty()) where.glob("r.name_lower", ascii_lower(f.structure_name_glob));
  if (!f.laterality.empty()) where.equal("r.laterality", f.laterality);
  // Rows without stored values pass (stage 2 decides them); the others must satisfy every
  // condition. Names and operators are checked (validate_stage1_filter) and become code constants.
  // As two searches in a subquery rather than an OR in the main one: the statistics SQLite keeps
  // (PRAGMA optimize at close) may date from before precompute stored anything, when the partial
  // index held every row; the OR was then planned as a scan of the whole table.
  if (!f.stored_features.empty()) {
    std::vector<SqlConditions::NumberComparison> all;
    for (const StoredFeatureCondition& c : f.stored_features)
      all.push_back({c.name, c.op == "!=" ? "<>" : c.op, c.value});
    where.all_unless("structure_id", "stage1_rows", "features_stored = 0", all);
  }
  return where;
}

}  // namespace

Result<std::vector<std::string>> SqliteStore::stage1_plan(const Stage1Filter& f, int64_t limit) {
  SOIQ_RETURN_IF_ERROR(validate_stage1_filter(f));
  const SqlConditions where = stage1_conditions(f);
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
  const SqlConditions where = stage1_conditions(f);
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
