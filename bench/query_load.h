#pragma once
// Loading the `soiq-bench query` cohort (query_cohort.h).
//
// load_background: the patients that do not match stage 1, each with its study and one structure
// on a shared surface blob, straight through db::SqliteStore (one transaction per structure, as
// the server would do it) into `db_path`: written in a folder on tmpfs (/dev/shm), where fsync is
// free, then copied there. These rows only need to exist, and 100,000 fsync'd commits would
// dominate the benchmark's set-up (a million on disk took more than half an hour).
// upload_matched: the matched patients through the real client to the real server: per patient
// its MR image (NIfTI) and its 10 surfaces (binary PLY), files prepared beforehand in `work_dir`
// (not timed), uploads timed, spread over `threads` clients.
// Errors: the store's or the client's, naming the patient.

#include <string>
#include <vector>

#include "bench/query_cohort.h"
#include "core/base/status.h"

namespace soiq::bench {

struct LoadFigures {
  int64_t patients = 0;
  int64_t structures = 0;
  int64_t images = 0;
  int64_t surface_bytes = 0, image_bytes = 0;  // file bytes sent
  int64_t triangles = 0;
  double seconds = 0;  // background: the whole load; matched: surfaces and images together
  double surface_seconds = 0, image_seconds = 0;
};

Result<LoadFigures> load_background(const std::string& db_path, const std::vector<CohortPatient>& cohort,
                                    const QueryCohortSize& size);

Result<LoadFigures> upload_matched(const std::string& address, const std::string& work_dir,
                                   const std::vector<CohortPatient>& cohort, const QueryCohortSize& size, int threads);

}  // namespace soiq::bench
