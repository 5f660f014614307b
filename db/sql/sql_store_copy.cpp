// SqlStore::copy_to and table_digests: everything a store holds, copied into another store of
// either backend (soiq-admin migrate) and compared table by table. Rows are copied as they are,
// keys included, so structure ids and every reference stay valid; the columns are read from the
// source (SELECT *), the same in both schemas (tests/db/pg_schema_test.cpp holds them together).
#include <algorithm>
#include <cstring>
#include <variant>

#include "db/sha256.h"
#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"

namespace soiq::db {
namespace {

// The tables that hold records, parents before children, each with its key (the copy's and the
// digest's order). Replicas and stage-2 work are the running replicas' state, not records.
struct Table {
  const char* name;
  const char* key;
};
constexpr Table kTables[] = {
    {"patients", "pk"},
    {"studies", "pk"},
    {"image_blobs", "sha256"},
    {"instance_files", "sha256"},
    {"series", "pk"},
    {"instances", "sop_instance_uid"},
    {"surfaces", "sha256"},
    {"structures", "id"},
    {"stored_features", "structure_id"},
    {"precompute_queue", "structure_id"},
    {"feature_cache", "key, entry"},
    {"stage1_rows", "structure_id"},
};

// Identity columns whose sequence PostgreSQL must be moved past the copied keys.
constexpr Table kIdentities[] = {{"patients", "pk"}, {"studies", "pk"}, {"series", "pk"}, {"structures", "id"}};

using Value = std::variant<std::monostate, int64_t, double, std::string>;
struct Cell {
  Value value;
  bool blob = false;
};

Cell read_cell(const SqlStatement& q, int col) {
  switch (q.value_type(col)) {
    case SqlValueType::kNull:
      return {};
    case SqlValueType::kInteger:
      return {q.int64(col)};
    case SqlValueType::kReal:
      return {q.real(col)};
    case SqlValueType::kText:
      return {std::string(q.text_view(col))};
    case SqlValueType::kBlob:
      return {std::string(q.blob_view(col)), true};
  }
  return {};
}

size_t cell_bytes(const Cell& c) {
  const auto* s = std::get_if<std::string>(&c.value);
  return s ? s->size() : 8;
}

// A batch goes out as one INSERT of many rows: within both engines' parameter limits, and a bound
// on the bytes held (blobs).
constexpr size_t kMaxParameters = 30000;
constexpr size_t kMaxBatchBytes = size_t(64) << 20;

Status insert_rows(SqlSession& to, const std::string& table, const std::vector<std::string>& columns,
                   const std::vector<std::vector<Cell>>& rows) {
  if (rows.empty()) return ok_status();
  std::string sql = "INSERT INTO " + table + "(";
  for (size_t i = 0; i < columns.size(); ++i) sql += (i ? ", " : "") + columns[i];
  sql += ") VALUES ";
  int n = 0;
  for (size_t r = 0; r < rows.size(); ++r) {
    sql += r ? ", (" : "(";
    for (size_t i = 0; i < columns.size(); ++i) sql += (i ? ", ?" : "?") + std::to_string(++n);
    sql += ")";
  }
  SOIQ_ASSIGN_OR_RETURN(SqlStatement ins, to.prepare(sql));
  n = 0;
  for (const std::vector<Cell>& row : rows) {
    for (const Cell& cell : row) {
      ++n;
      if (std::holds_alternative<std::monostate>(cell.value)) {
        ins.bind_null(n);
      } else if (const auto* i = std::get_if<int64_t>(&cell.value)) {
        ins.bind(n, *i);
      } else if (const auto* d = std::get_if<double>(&cell.value)) {
        ins.bind(n, *d);
      } else if (cell.blob) {
        ins.bind_blob(n, std::get<std::string>(cell.value));
      } else {
        ins.bind(n, std::string_view(std::get<std::string>(cell.value)));
      }
    }
  }
  return ins.run();
}

Status copy_table(SqlSession& from, SqlSession& to, const Table& t,
                  const std::function<void(const std::string&, int64_t)>& progress) {
  SOIQ_ASSIGN_OR_RETURN(const bool exists, table_exists(from, t.name));
  if (!exists) return ok_status();  // a source of an older schema: the table's rows are none
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, from.prepare(std::string("SELECT * FROM ") + t.name + " ORDER BY " + t.key));
  std::vector<std::string> columns;
  std::vector<std::vector<Cell>> batch;
  size_t bytes = 0;
  int64_t copied = 0;
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) break;
    if (columns.empty()) {
      for (int i = 0; i < q.column_count(); ++i) columns.push_back(q.column_name(i));
    }
    std::vector<Cell>& cells = batch.emplace_back();
    for (int i = 0; i < int(columns.size()); ++i) {
      cells.push_back(read_cell(q, i));
      bytes += cell_bytes(cells.back());
    }
    if ((batch.size() + 1) * columns.size() > kMaxParameters || bytes > kMaxBatchBytes) {
      SOIQ_RETURN_IF_ERROR(insert_rows(to, t.name, columns, batch));
      copied += int64_t(batch.size());
      if (progress) progress(t.name, copied);
      batch.clear();
      bytes = 0;
    }
  }
  SOIQ_RETURN_IF_ERROR(insert_rows(to, t.name, columns, batch));
  copied += int64_t(batch.size());
  if (progress) progress(t.name, copied);
  return ok_status();
}

// A row's canonical bytes for the digest: its columns in name order (the two schemas may order a
// table's columns differently), each value with its type and length, so that "ab","c" and "a","bc"
// differ, and doubles by their bits (the backends keep them exactly).
void digest_row(const SqlStatement& q, const std::vector<int>& by_name, Sha256& h) {
  for (const int i : by_name) {
    const Cell c = read_cell(q, i);
    std::string part = q.column_name(i) + "=";
    if (const auto* n = std::get_if<int64_t>(&c.value)) {
      part += "i" + std::to_string(*n);
    } else if (const auto* d = std::get_if<double>(&c.value)) {
      uint64_t bits = 0;
      std::memcpy(&bits, d, sizeof bits);
      part += "r" + std::to_string(bits);
    } else if (const auto* s = std::get_if<std::string>(&c.value)) {
      part += "s" + std::to_string(s->size()) + ":" + *s;  // text and blob alike: the same bytes
    } else {
      part += "n";
    }
    part += ';';
    h.update(part.data(), part.size());
  }
}

constexpr char kSqliteTableExistsSql[] = R"sql(
  SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?1)sql";
constexpr char kPostgresTableExistsSql[] = R"sql(
  SELECT count(*) FROM pg_catalog.pg_tables WHERE schemaname = current_schema() AND tablename = ?1)sql";
constexpr char kSqliteColumnExistsSql[] = R"sql(
  SELECT count(*) FROM pragma_table_info(?1) WHERE name = ?2)sql";
constexpr char kPostgresColumnExistsSql[] = R"sql(
  SELECT count(*) FROM information_schema.columns
  WHERE table_schema = current_schema() AND table_name = ?1 AND column_name = ?2)sql";

}  // namespace

Result<bool> table_exists(SqlSession& c, const std::string& table) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(c.dialect() == SqlDialect::kPostgres ? kPostgresTableExistsSql
                                                                                       : kSqliteTableExistsSql));
  q.bind(1, table);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  return row && q.int64(0) > 0;
}

Result<bool> column_exists(SqlSession& c, const std::string& table, const std::string& column) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(c.dialect() == SqlDialect::kPostgres ? kPostgresColumnExistsSql
                                                                                       : kSqliteColumnExistsSql));
  q.bind(1, table);
  q.bind(2, column);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  return row && q.int64(0) > 0;
}

Status SqlStore::copy_to(SqlStore& to, const std::function<void(const std::string&, int64_t)>& progress) {
  SOIQ_ASSIGN_OR_RETURN(const Counts target, to.counts());
  if (target.patients != 0 || target.structures != 0 || target.surfaces != 0 || target.series != 0 ||
      target.cached_features != 0) {
    return failed_precondition("the target store is not empty; migrate copies into an empty store only");
  }
  // One transaction on each side: the copy is a snapshot of the source, and lands whole or not at all.
  return to.write([&](SqlSession& target_session) -> Status {
    SOIQ_RETURN_IF_ERROR(read([&](SqlSession& source) -> Status {
      for (const Table& t : kTables) SOIQ_RETURN_IF_ERROR(copy_table(source, target_session, t, progress));
      return ok_status();
    }));
    if (target_session.dialect() != SqlDialect::kPostgres) return ok_status();
    for (const Table& t : kIdentities) {
      // The next key the sequence hands out is above every copied one.
      SOIQ_ASSIGN_OR_RETURN(
          SqlStatement next,
          target_session.prepare(std::string("SELECT setval(pg_get_serial_sequence('") + t.name + "', '" + t.key +
                                 "'), coalesce(max(" + t.key + "), 0) + 1, false) FROM " + t.name));
      SOIQ_RETURN_IF_ERROR(next.run());
    }
    return ok_status();
  });
}

namespace {

// One table's rows and digest (SqlStore::table_digests). A store of an older schema (opened read
// only) lacks the later tables: each is read as an empty one.
Result<TableDigest> digest_table(SqlSession& c, const Table& t) {
  Sha256 h;
  TableDigest d{t.name, 0, ""};
  SOIQ_ASSIGN_OR_RETURN(const bool exists, table_exists(c, t.name));
  if (exists) {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(std::string("SELECT * FROM ") + t.name + " ORDER BY " + t.key));
    std::vector<int> by_name;
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      if (by_name.empty()) {
        for (int i = 0; i < q.column_count(); ++i) by_name.push_back(i);
        std::sort(by_name.begin(), by_name.end(), [&](int a, int b) { return q.column_name(a) < q.column_name(b); });
      }
      ++d.rows;
      digest_row(q, by_name, h);
    }
  }
  d.sha256 = h.hex_digest();
  return d;
}

}  // namespace

Result<std::vector<TableDigest>> SqlStore::table_digests() {
  std::vector<TableDigest> out;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    out.clear();
    for (const Table& t : kTables) {
      SOIQ_ASSIGN_OR_RETURN(TableDigest d, digest_table(c, t));
      out.push_back(std::move(d));
    }
    return ok_status();
  }));
  return out;
}

}  // namespace soiq::db
