#pragma once
// Stage 1 of a query (docs/DESIGN.md "Queries") in SQL, shared by both backends: every condition of the
// filter is on stage1_rows (alias r), the narrow table each backend keeps in step with its records,
// so the query reads one table and the records are joined only for the rows it returns.

#include <cstdint>
#include <string>

#include "db/sql/sql_conditions.h"
#include "db/store.h"

namespace soiq::db {

// The filter's conditions. Names and operators of stored-feature conditions must have been checked
// (validate_stage1_filter): they become SQL text.
SqlConditions stage1_conditions(const Stage1Filter& f, SqlDialect dialect);

// "SELECT structure_id, twin id or NULL FROM stage1_rows r WHERE …" ordered by id, at most `limit`.
std::string stage1_ids_sql(const SqlConditions& where, const Stage1Filter& f, int64_t limit);
// The number of rows the conditions keep.
std::string stage1_count_sql(const SqlConditions& where);

}  // namespace soiq::db
