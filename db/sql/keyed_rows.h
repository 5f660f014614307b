#pragma once
// Rows for many keys at once, in the fewest statements each backend allows:
//   SQLite      `… IN (?1, …, ?n) …`, the keys in chunks of at most kMaxKeysPerStatement, each
//               chunk's count padded to a power of two with its last key repeated, so a list of any
//               length is read by at most 9 statement texts, each prepared once per connection;
//   PostgreSQL  `… = ANY(?1::bigint[]) …` (or text[]), every key in one array parameter: one
//               statement text, one round trip, one generic plan (an IN list of 128 parameters cost
//               PostgreSQL more to bind and plan than to run).

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "db/sql/record_sql.h"
#include "db/sql/sql_conditions.h"
#include "db/sql/sql_session.h"

namespace soiq::db {

inline constexpr size_t kMaxKeysPerStatement = 256;

// A statement over keys: `before` ends with the keyed column ("… WHERE s.id"), `after` follows the
// keys' condition ("ORDER BY …" or empty).
struct KeyedSql {
  std::string_view before, after;
};

// Runs `sql` over `keys` (int64_t or std::string) and calls row(statement) on every row (a row that
// returns a Status not ok stops there and returns it). A key given twice may give its rows twice
// (on SQLite when the copies fall in two chunks): callers that must not see them twice pass each key
// once. Rows come in the statement's order within a chunk; on SQLite chunks follow the keys' order.
template <typename Key, typename Row>
Status for_each_keyed_row(SqlSession& c, const std::vector<Key>& keys, const KeyedSql& sql, const Row& row) {
  static_assert(std::is_same_v<Key, int64_t> || std::is_same_v<Key, std::string>, "keys are integers or text");
  const auto each_row = [&row](SqlStatement& q) -> Status {
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool more, q.step());
      if (!more) return ok_status();
      if constexpr (std::is_same_v<decltype(row(q)), Status>) {
        SOIQ_RETURN_IF_ERROR(row(q));
      } else {
        row(q);
      }
    }
  };
  const auto text = [&sql](std::string_view condition) {
    return std::string(sql.before).append(condition).append(" ").append(sql.after);
  };
  if (keys.empty()) return ok_status();
  if (c.dialect() == SqlDialect::kPostgres) {
    SOIQ_ASSIGN_OR_RETURN(
        SqlStatement q, c.prepare(text(std::is_same_v<Key, int64_t> ? " = ANY(?1::bigint[])" : " = ANY(?1::text[])")));
    q.bind(1, array_literal(keys));
    return each_row(q);
  }
  for (size_t begin = 0; begin < keys.size(); begin += kMaxKeysPerStatement) {
    const size_t count = std::min(kMaxKeysPerStatement, keys.size() - begin);
    const size_t padded = std::bit_ceil(count);
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(text(" IN (" + parameter_list(padded) + ")")));
    for (size_t i = 0; i < padded; ++i) q.bind(int(i + 1), keys[begin + std::min(i, count - 1)]);
    SOIQ_RETURN_IF_ERROR(each_row(q));
  }
  return ok_status();
}

}  // namespace soiq::db
