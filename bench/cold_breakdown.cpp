#include "bench/cold_breakdown.h"

#include <chrono>
#include <map>
#include <memory>

#include "bench/clock.h"
#include "core/features/intensity_features.h"
#include "core/features/structure_features.h"
#include "core/features/surface_shape.h"
#include "core/geometry/mesh_defects.h"
#include "core/regions/regions.h"
#include "core/regions/resample.h"
#include "core/voxelize/voxelize_1d.h"
#include "db/image_blob.h"
#include "db/sqlite/sqlite_store.h"
#include "db/surface_blob.h"
#include "server/app/grid_choice.h"

namespace soiq::bench {
namespace {

constexpr int64_t kBeforeSampling = 10;

// Sums the time of each named part, in the order parts first appear.
class Parts {
 public:
  template <typename F>
  auto run(const std::string& part, F&& f) {
    const Clock::time_point t0 = Clock::now();
    auto result = f();
    add(part, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    return result;
  }
  void add(const std::string& part, double ms) {
    auto it = index_.find(part);
    if (it == index_.end()) {
      it = index_.emplace(part, parts_.size()).first;
      parts_.emplace_back(part, 0.0);
    }
    parts_[it->second].second += ms;
  }
  std::vector<std::pair<std::string, double>> take() { return std::move(parts_); }

 private:
  std::map<std::string, size_t> index_;
  std::vector<std::pair<std::string, double>> parts_;
};

}  // namespace

Result<ColdBreakdown> cold_breakdown(const std::string& db_path, const db::Stage1Filter& filter) {
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqliteStore> store, db::SqliteStore::open(db_path, {}));
  ColdBreakdown out;
  Parts parts;
  const Clock::time_point t0 = Clock::now();
  SOIQ_ASSIGN_OR_RETURN(std::vector<db::Candidate> candidates, store->stage1(filter, 100000));
  out.stage1_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  const server::GridChoice choice;  // the default: axis-aligned 1 mm grid, 2-voxel margin
  SOIQ_ASSIGN_OR_RETURN(const RegionSpec shell, parse_region("shell:3"));
  std::map<std::string, std::shared_ptr<const Image>> images;
  std::vector<db::SurfaceFeatures> to_store;
  int64_t sampled = 0;  // by study, as the server caches them
  for (const db::Candidate& cand : candidates) {
    const db::StructureRecord& s = cand.structure;
    SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, store->list_series(s.study_uid));
    SOIQ_ASSIGN_OR_RETURN(const server::ResolvedGrid grid,
                          server::resolve_grid(choice, s, series, shell.radius_mm, 500'000'000));
    SOIQ_ASSIGN_OR_RETURN(const db::SeriesRecord mr, server::find_series("MR", series, s.study_uid));
    SOIQ_ASSIGN_OR_RETURN(const std::string blob,
                          parts.run("surface blob read", [&] { return store->get_surface_blob(s.surface.sha256); }));
    SOIQ_ASSIGN_OR_RETURN(const TriangleMesh mesh,
                          parts.run("surface blob decode", [&] { return db::decode_surface(blob); }));
    VoxelizeOptions options;
    options.known_defects = MeshDefects{};  // checked at upload, as the server trusts it
    SOIQ_ASSIGN_OR_RETURN(Voxelization v,
                          parts.run("1D conversion", [&] { return voxelize_1d(mesh, grid.geometry, options); }));
    // What the server did before (hull for any surface feature, mesh copied into StructureInput):
    // on one structure in 10 only, as the hull costs ~100x the rest; totals are extrapolated.
    const bool sample = out.structures % kBeforeSampling == 0;
    if (sample) {
      parts.run("(before) mesh copy into StructureInput", [&] { return TriangleMesh(mesh); });
      ++sampled;
    }
    SOIQ_ASSIGN_OR_RETURN(const VolumeShape vs, parts.run("volume features", [&] { return volume_shape(v.volume); }));
    SOIQ_ASSIGN_OR_RETURN(const SurfaceShape hull_free, parts.run("surface features, hull-free (volume + area)", [&] {
      return surface_shape(mesh, grid.geometry.direction, HullPart::kSkip);
    }));
    const double sphericity = hull_free.sphericity;
    if (sample) {
      SOIQ_ASSIGN_OR_RETURN(const SurfaceShape ss,
                            parts.run("(before) surface features by surface_shape, with hull",
                                      [&] { return surface_shape(mesh, grid.geometry.direction); }));
      if (ss.sphericity != sphericity)
        return internal_error("structure " + std::to_string(s.id) +
                              ": hull-free sphericity differs from surface_shape's");
    }
    SOIQ_ASSIGN_OR_RETURN(const RunLengthVolume r,
                          parts.run("shell region (3 mm)", [&] { return region(v.volume, shell); }));
    auto it = images.find(s.study_uid);
    if (it == images.end()) {
      SOIQ_ASSIGN_OR_RETURN(const std::string image_blob,
                            parts.run("image read", [&] { return store->get_image_blob(mr.series_uid); }));
      SOIQ_ASSIGN_OR_RETURN(Image image,
                            parts.run("image decode", [&] { return db::decode_image(image_blob, mr.geometry); }));
      it = images.emplace(s.study_uid, std::make_shared<const Image>(std::move(image))).first;
    }
    SOIQ_ASSIGN_OR_RETURN(RegionSamples samples,
                          parts.run("resampling", [&] { return resample(*it->second, r, Interpolation::kNearest); }));
    SOIQ_ASSIGN_OR_RETURN(const IntensityFeatures f, parts.run("intensity features", [&] {
      return intensity_features(std::move(samples.values));
    }));
    const std::string key = "bench|" + s.surface.sha256 + "|" + grid.key;
    const std::vector<db::CachedFeature> entries = {{key, "voxel_volume_mm3", {vs.voxel_volume_mm3}},
                                                    {key, "sphericity", {sphericity}},
                                                    {key, "mean|shell:3|" + mr.sha256 + "|nearest", {f.mean}}};
    to_store.push_back({s.surface.sha256, entries});
    ++out.structures;
    out.triangles += int64_t(mesh.triangles.size());
    out.voxels += vs.voxel_count;
    out.shell_voxels += voxel_count(r);
    out.values[s.id] = {vs.voxel_volume_mm3, sphericity, f.mean};
  }
  // The server writes what its workers computed in batches, one transaction per round of the query
  // thread (query_engine.cpp): here all in one.
  SOIQ_RETURN_IF_ERROR(parts.run("cache write", [&] { return store->put_cached_features(to_store); }));
  out.total_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  out.parts_ms = parts.take();
  for (auto& [part, ms] : out.parts_ms)
    if (part.rfind("(before)", 0) == 0 && sampled > 0) ms *= double(out.structures) / double(sampled);
  return out;
}

}  // namespace soiq::bench
