#include "bench/conversions_alone.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "bench/clock.h"
#include "core/regions/regions.h"
#include "core/voxelize/voxelize_1d.h"
#include "db/sqlite/sqlite_store.h"
#include "db/surface_blob.h"
#include "server/app/grid_choice.h"

namespace soiq::bench {

namespace {

struct ThreadSums {
  double convert_ms = 0, read_decode_ms = 0;
  Status status;
};

}  // namespace

Result<ConversionsAlone> conversions_alone(const std::string& db_path, const db::Stage1Filter& filter, int threads) {
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqliteStore> store, db::SqliteStore::open(db_path, {}));
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::Candidate> candidates, store->stage1(filter, 100000));
  const server::GridChoice choice;  // the query's grid: axis-aligned 1 mm, margin grown for the shell
  SOIQ_ASSIGN_OR_RETURN(const RegionSpec shell, parse_region("shell:3"));
  // Grids first, on this thread: the store is read by one thread at a time.
  struct Work {
    std::string sha256;
    ImageGeometry grid;
  };
  std::vector<Work> work;
  for (const db::Candidate& c : candidates) {
    SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, store->list_series(c.structure.study_uid));
    SOIQ_ASSIGN_OR_RETURN(const server::ResolvedGrid grid,
                          server::resolve_grid(choice, c.structure, series, shell.radius_mm, 500'000'000));
    work.push_back({c.structure.surface.sha256, grid.geometry});
  }
  std::mutex store_mutex;
  std::vector<ThreadSums> sums(static_cast<size_t>(std::max(1, threads)));
  auto run = [&](size_t t) {
    ThreadSums& mine = sums[t];
    for (size_t i = t; i < work.size() && mine.status.ok(); i += sums.size()) {
      const Clock::time_point t0 = Clock::now();
      Result<std::string> blob = [&] {
        std::lock_guard<std::mutex> lock(store_mutex);
        return store->get_surface_blob(work[i].sha256);
      }();
      if (!blob.ok()) {
        mine.status = blob.status();
        break;
      }
      Result<TriangleMesh> mesh = db::decode_surface(*blob);
      mine.read_decode_ms += ms_since(t0);
      if (!mesh.ok()) {
        mine.status = mesh.status();
        break;
      }
      VoxelizeOptions options;
      options.known_defects = MeshDefects{};  // checked at upload, as the server trusts it
      const Clock::time_point t1 = Clock::now();
      const Result<Voxelization> v = voxelize_1d(*mesh, work[i].grid, options);
      mine.convert_ms += ms_since(t1);
      if (!v.ok()) mine.status = v.status();
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < sums.size(); ++t) pool.emplace_back(run, t);
  run(0);
  for (std::thread& th : pool) th.join();
  ConversionsAlone out;
  out.threads = int(sums.size());
  out.structures = int64_t(work.size());
  for (const ThreadSums& s : sums) {
    SOIQ_RETURN_IF_ERROR(s.status);
    out.convert_ms = std::max(out.convert_ms, s.convert_ms);
    out.read_decode_ms = std::max(out.read_decode_ms, s.read_decode_ms);
  }
  return out;
}

}  // namespace soiq::bench
