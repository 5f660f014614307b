#pragma once
// The yardstick of the cold query in `soiq-bench query`: the same stage-1 candidates' surfaces
// converted alone, with nothing else, on `threads` threads as soiqd's workers would share them
// (each thread takes every threads-th candidate), on the grid the query uses. Each surface is read
// and decoded first, untimed; `convert_ms` is the conversions' wall time (the busiest thread's
// sum), `read_decode_ms` what reading and decoding them took on the same threads (also the busiest
// thread's sum), so a reader can weigh the query against either yardstick.
// Errors: the store's and the conversions'.

#include <string>

#include "core/base/status.h"
#include "db/store.h"

namespace soiq::bench {

struct ConversionsAlone {
  int threads = 1;
  int64_t structures = 0;
  double convert_ms = 0;
  double read_decode_ms = 0;
};

Result<ConversionsAlone> conversions_alone(const std::string& db_path, const db::Stage1Filter& filter, int threads);

}  // namespace soiq::bench
