// SqlStore::stage1: the structured half of a query (docs/DESIGN.md "Queries"): the ids from one query
// over stage1_rows (stage1_sql.h), then their records read in bulk, a few statements for a
// thousand candidates (on PostgreSQL every statement is a round trip).
#include <map>
#include <optional>
#include <utility>

#include "db/sql/keyed_rows.h"
#include "db/sql/record_sql.h"
#include "db/sql/sql_store.h"
#include "db/sql/stage1_sql.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

// Structures with the keys of their study and patient; patients and studies by key. The key
// list follows each.
constexpr char kStructuresByIdSql[] = R"sql(
  WHERE s.id)sql";
constexpr char kStudyAndPatientKeyColumns[] = R"sql(
  st.pk, p.pk)sql";
constexpr char kPatientsByKeySql[] = R"sql(
  FROM patients p
  WHERE p.pk)sql";
constexpr char kStudiesByKeySql[] = R"sql(
  FROM studies st
  JOIN patients p ON p.pk = st.patient_pk
  WHERE st.pk)sql";

template <typename T>
std::vector<int64_t> keys_of(const std::map<int64_t, T>& m) {
  std::vector<int64_t> keys;
  for (const auto& [key, value] : m) keys.push_back(key);
  return keys;
}

}  // namespace

Result<std::vector<Candidate>> SqlStore::stage1(const Stage1Filter& f, int64_t limit) {
  if (limit < 1) return invalid_argument("stage-1 limit must be >= 1, got " + std::to_string(limit));
  SOIQ_RETURN_IF_ERROR(validate_stage1_filter(f));
  std::vector<Candidate> out;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    out.clear();
    const SqlConditions where = stage1_conditions(f, c.dialect());
    // The matching ids from stage1_rows alone, at most limit + 1 of them: the filters choose the
    // plan on that one narrow table, and no record is built before we know there are not too many.
    // With twins, each hit's twin id comes from the same query (a self-join of structures).
    std::vector<std::pair<int64_t, std::optional<int64_t>>> ids;
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(stage1_ids_sql(where, f, limit + 1)));
      where.bind(q);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        ids.emplace_back(q.int64(0), q.is_null(1) ? std::nullopt : std::optional<int64_t>(q.int64(1)));
      }
    }
    if (int64_t(ids.size()) > limit) {
      // Only for the message: the full count, in the same snapshot.
      SOIQ_ASSIGN_OR_RETURN(SqlStatement all, c.prepare(stage1_count_sql(where)));
      where.bind(all);
      SOIQ_ASSIGN_OR_RETURN(const bool counted, all.step());
      const int64_t total = counted ? all.int64(0) : limit + 1;
      return resource_exhausted("stage 1 matches " + std::to_string(total) + " structures, more than the limit of " +
                                std::to_string(limit) + "; narrow the stage-1 filter");
    }
    // Then the records: the structures and twins, and each patient and study once however many
    // of their structures the filter keeps (each has count subqueries).
    struct Keyed {
      StructureRecord structure;
      int64_t study_pk = 0, patient_pk = 0;
    };
    std::map<int64_t, Keyed> structures;
    for (const auto& [id, twin] : ids) {
      structures[id];
      if (twin) structures[*twin];
    }
    static const std::string structures_sql =
        select_sql({kStructureColumns, kStudyAndPatientKeyColumns}, {kStructureFrom, kStructuresByIdSql});
    SOIQ_RETURN_IF_ERROR(
        for_each_keyed_row(c, keys_of(structures), KeyedSql{structures_sql, ""}, [&](const SqlStatement& q) {
          structures[q.int64(0)] = {read_structure(q, 0), q.int64(kStructureColumnCount),
                                    q.int64(kStructureColumnCount + 1)};
        }));
    std::map<int64_t, PatientRecord> patients;
    std::map<int64_t, StudyRecord> studies;
    for (const auto& [id, twin] : ids) {
      const Keyed& s = structures[id];
      if (s.structure.id != id) return internal_error("structure " + std::to_string(id) + " vanished in a read");
      patients[s.patient_pk];
      studies[s.study_pk];
    }
    // The key goes last in these selects, after the record's columns.
    static const std::string patients_sql = select_sql({kPatientColumns, "p.pk"}, {kPatientsByKeySql});
    SOIQ_RETURN_IF_ERROR(for_each_keyed_row(
        c, keys_of(patients), KeyedSql{patients_sql, ""},
        [&](const SqlStatement& q) { patients[q.int64(kPatientColumnCount)] = read_patient(q, 0); }));
    static const std::string studies_sql = select_sql({kStudyColumns, "st.pk"}, {kStudiesByKeySql});
    SOIQ_RETURN_IF_ERROR(for_each_keyed_row(c, keys_of(studies), KeyedSql{studies_sql, ""}, [&](const SqlStatement& q) {
      studies[q.int64(kStudyColumnCount)] = read_study(q, 0);
    }));
    out.reserve(ids.size());
    for (const auto& [id, twin] : ids) {
      const Keyed& s = structures[id];
      Candidate cand{s.structure, patients[s.patient_pk], studies[s.study_pk], std::nullopt};
      if (twin) {
        const Keyed& t = structures[*twin];
        if (t.structure.id != *twin) return internal_error("twin " + std::to_string(*twin) + " vanished in a read");
        cand.twin = t.structure;
      }
      out.push_back(std::move(cand));
    }
    return ok_status();
  }));
  return out;
}

}  // namespace soiq::db
