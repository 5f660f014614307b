#pragma once
// Rows for many keys at once: `… IN (?1, …, ?n) …` statements, the keys in chunks of at most
// kMaxKeysPerStatement, each chunk's count padded to a power of two with its last key repeated, so
// a list of any length is read in few round trips by at most 9 statement texts, each prepared once
// per connection (the PostgreSQL session prepares a text on its second use).

#include <algorithm>
#include <bit>
#include <string>
#include <type_traits>
#include <vector>

#include "db/sql/record_sql.h"
#include "db/sql/sql_session.h"

namespace soiq::db {

inline constexpr size_t kMaxKeysPerStatement = 256;

// Runs sql_for(n) (a statement whose parameters ?1..?n are the chunk's keys: parameter_list(n) in
// an IN list) for each chunk of `keys`, and calls row(statement) on every row (a row that returns
// a Status not ok stops there and returns it). A key repeated, in a
// chunk or across chunks, gives its rows again: callers that must not see them twice pass each key
// once.
template <typename Key, typename SqlFor, typename Row>
Status for_each_keyed_row(SqlSession& c, const std::vector<Key>& keys, const SqlFor& sql_for, const Row& row) {
  for (size_t begin = 0; begin < keys.size(); begin += kMaxKeysPerStatement) {
    const size_t count = std::min(kMaxKeysPerStatement, keys.size() - begin);
    const size_t padded = std::bit_ceil(count);
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(sql_for(padded)));
    for (size_t i = 0; i < padded; ++i) q.bind(int(i + 1), keys[begin + std::min(i, count - 1)]);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool more, q.step());
      if (!more) break;
      if constexpr (std::is_same_v<decltype(row(q)), Status>) {
        SOIQ_RETURN_IF_ERROR(row(q));
      } else {
        row(q);
      }
    }
  }
  return ok_status();
}

}  // namespace soiq::db
