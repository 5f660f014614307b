// The SQL of stage 1 (docs/DESIGN.md "Queries"), the same in both backends but for the dialect of its
// conditions: see stage1_sql.h.
#include "db/sql/stage1_sql.h"

#include "db/sql/glob_range.h"

namespace soiq::db {
namespace {

// A hit's contralateral twin: same study, same name in ASCII lower case (lower(), as
// stage1_rows.name_lower; PostgreSQL's lower() of the store's "C" columns is ASCII too), the other laterality; the
// lowest id when a study has several.
constexpr char kTwinIdColumn[] = R"sql(
  (SELECT t.id FROM structures s JOIN structures t
     ON t.study_pk = s.study_pk AND lower(t.name) = lower(s.name)
    AND t.laterality = CASE s.laterality WHEN 'L' THEN 'R' WHEN 'R' THEN 'L' END
   WHERE s.id = r.structure_id ORDER BY t.id LIMIT 1))sql";
constexpr char kNoTwinIdColumn[] = R"sql( NULL)sql";

// The stage-1 rows the filter keeps: its conditions (" AND …", stage1_conditions) follow.
constexpr char kStage1RowsSql[] = R"sql(
  FROM stage1_rows r
  WHERE true)sql";

// The ids of the rows, each with its twin's id or NULL, at most `limit` of them.
constexpr char kStage1IdsSql[] = R"sql(
  SELECT r.structure_id,)sql";
constexpr char kStage1IdsOrderSql[] = R"sql(
  ORDER BY r.structure_id
  LIMIT )sql";
// With conditions on stored features: "+" (a no-op to PostgreSQL) keeps SQLite from scanning the whole table in id
// order (to spare a sort) where the searches of the unstored rows' partial index and of a feature's index read only the
// rows that can match; the few it finds are then sorted.
constexpr char kStage1IdsOrderUnindexedSql[] = R"sql(
  ORDER BY +r.structure_id
  LIMIT )sql";

constexpr char kStage1CountSql[] = R"sql(
  SELECT count(*))sql";

}  // namespace

std::string stage1_ids_sql(const SqlConditions& where, const Stage1Filter& f, int64_t limit) {
  return std::string(kStage1IdsSql) + (f.twins ? kTwinIdColumn : kNoTwinIdColumn) + kStage1RowsSql + where.sql() +
         (f.stored_features.empty() ? kStage1IdsOrderSql : kStage1IdsOrderUnindexedSql) + std::to_string(limit);
}

std::string stage1_count_sql(const SqlConditions& where) {
  return std::string(kStage1CountSql) + kStage1RowsSql + where.sql();
}

// Every condition is on stage1_rows (alias r), so the query reads one narrow table and joins the
// records only for the rows it returns.
SqlConditions stage1_conditions(const Stage1Filter& f, SqlDialect dialect) {
  SqlConditions where(dialect);
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
  if (!f.modality.empty()) where.contains_delimited("r.modalities", f.modality);
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
    for (const StoredFeatureCondition& c : f.stored_features) all.push_back({c.name, sql_operator(c.op), c.value});
    where.all_unless("structure_id", "stage1_rows", "features_stored = 0", all);
  }
  return where;
}

}  // namespace soiq::db
