#pragma once
// Features of stored structures, computed on demand and cached (docs/DESIGN.md "Queries": cached under
// surface hash, geometry and feature-definition version). Used by ComputeFeatures for one structure
// and by the query engine for many.
//
// A FeatureAsk says which features, on which regions and images, on which grid. plan() turns it
// into what one structure needs (its grid, its images, its cache key and entries) without decoding
// anything, so a query can look up the cache for all candidates in one round trip; compute() then
// converts, measures and stores what was missing.
//
// Cache entries are "name" for shape features and "name|region|image sha256|interpolation" for
// intensity features, under the key "v<definition version>|<surface sha256>|<grid key>|<fill>".
// compute() caches every value the report gives, not only those asked.
//
// Errors: those of grid resolution (grid_choice.h), of finding an image (NOT_FOUND, naming the
// study), of the conversion (RESOURCE_EXHAUSTED grid, DATA_LOSS naming the structure for a damaged
// surface or image blob) and of the features
// (INVALID_ARGUMENT: empty region, image in another frame). CANCELLED when `cancelled` turns true.
// Thread-safe: many workers call compute() at once.

#include <atomic>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/base/coverage_volume.h"
#include "core/base/fill_rule.h"
#include "core/base/image.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/regions/regions.h"
#include "core/regions/resample.h"
#include "core/voxelize/memory_estimate.h"
#include "core/voxelize/voxelize_1d.h"
#include "db/store.h"
#include "server/app/grid_choice.h"
#include "server/app/memory_budget.h"
#include "server/util/lru_cache.h"

namespace soiq::server {

// The feature cache's entries carry feature_definitions_version() (core/features/feature_catalogue.h):
// bumping any definition there means old entries are never read again.

struct FeatureAsk {
  std::vector<std::string> names;   // validated names (validate_feature_names)
  std::vector<RegionSpec> regions;  // for intensity names; default inside
  std::vector<std::string> images;  // series uid or modality, per structure's study
  Interpolation interpolation = Interpolation::kNearest;
  GridChoice grid;
  FillRule fill_rule = FillRule::kNonZero;
};

// INVALID_ARGUMENT for an unknown name (listing the known ones), intensity names without an image,
// images without an intensity name. Empty names: every shape feature.
Status complete_feature_ask(FeatureAsk& ask);

// One value a plan wants, with the names the client gave.
struct WantedValue {
  std::string entry;  // cache entry
  std::string name, region, image;
};

struct FeaturePlan {
  db::StructureRecord structure;
  ResolvedGrid grid;
  std::vector<db::SeriesRecord> images;  // each series FeatureAsk::images names, once
  std::vector<size_t> image_of_ask;      // per FeatureAsk::images: its series' index in images
  std::string cache_key;
  std::vector<WantedValue> wants;
};

using FeatureValues = std::map<std::string, std::vector<double>>;  // entry -> value

class FeatureEngine {
 public:
  // The right to convert one structure on one grid: its estimated peak bytes held in the memory
  // budget. Only admit() makes one (there is no other constructor, and no copy), and convert()
  // takes one, so a conversion outside the budget does not compile; convert() refuses an admission
  // made for another structure or grid, and one whose bytes moved to another admission.
  class Admission {
   public:
    Admission(Admission&& other) noexcept
        : held_(std::move(other.held_)),
          structure_id_(std::exchange(other.structure_id_, -1)),
          geometry_(other.geometry_) {}
    Admission& operator=(Admission&& other) noexcept {
      held_ = std::move(other.held_);
      structure_id_ = std::exchange(other.structure_id_, -1);
      geometry_ = other.geometry_;
      return *this;
    }
    int64_t bytes() const { return held_.bytes(); }
    // Once converted, only the result stays: gives back all but `bytes`.
    void shrink_to(int64_t bytes) { held_.shrink_to(bytes); }

   private:
    friend class FeatureEngine;
    Admission(MemoryBudget::Reservation held, int64_t structure_id, const ImageGeometry& geometry)
        : held_(std::move(held)), structure_id_(structure_id), geometry_(geometry) {}
    MemoryBudget::Reservation held_;
    int64_t structure_id_ = -1;
    ImageGeometry geometry_;
  };

  // `budget` admits every conversion and computation by its estimated peak bytes (memory_budget.h).
  FeatureEngine(db::Store& store, int64_t max_grid_voxels, MemoryBudget& budget,
                int64_t cache_budget_bytes = int64_t(2) << 30);

  Result<FeaturePlan> plan(const db::StructureRecord& structure, const std::vector<db::SeriesRecord>& study_series,
                           const FeatureAsk& ask) const;

  // Computes the plan's features and stores them all in the feature cache, or, with `to_store`,
  // leaves them there for the caller to write with others in one transaction (the query engine).
  Result<FeatureValues> compute(const FeaturePlan& plan, const FeatureAsk& ask,
                                const std::atomic<bool>* cancelled = nullptr, db::SurfaceFeatures* to_store = nullptr);

  // The structure's stored surface, decoded (cached from its second use on: a pass over many
  // surfaces each used once does not fill the cache; lru_cache.h). DATA_LOSS naming the structure and its
  // surface when the blob is damaged: its checksum differs, or, for a blob without one, its mesh's
  // sha256 (db/surface_blob.h).
  Result<std::shared_ptr<const TriangleMesh>> surface(const db::StructureRecord& structure);
  // The structure on a grid by the 1D method (robust when the structure was uploaded so), under
  // `admitted` (admit() for this structure and grid; INTERNAL for another's).
  Result<Voxelization> convert(const Admission& admitted, const db::StructureRecord& structure,
                               const ImageGeometry& geometry, FillRule fill_rule);

  // The coverage fractions of `structure` on `geometry` with n x n lines per voxel (coverage_1d),
  // within `admitted` (admit() with WorkExtras::coverage_lines = n). FAILED_PRECONDITION for a
  // structure stored in robust mode (an open surface has no fractions).
  Result<CoverageVolume> cover(const Admission& admitted, const db::StructureRecord& structure,
                               const ImageGeometry& geometry, FillRule fill_rule, int lines_per_voxel);

  // What a piece of work will hold besides the conversion itself.
  struct WorkExtras {
    int coverage_lines = 0;    // n > 0: the work computes coverage fractions (cover), not runs
    bool features = false;     // structure_features on the runs
    bool mask_export = false;  // a dense mask written as NIfTI
    int fraction_bytes = 0;    // 1 or 4: dense coverage fractions of that size written as NIfTI
    int64_t image_voxels = 0;  // images decoded for intensities
    int regions = 0;           // regions with intensities
    int64_t other_bytes = 0;   // anything else the work holds (a picture's surface and file)
  };
  // Reserves the estimated peak bytes of converting `structure` on `geometry` plus `extras` in the
  // memory budget; RESOURCE_EXHAUSTED naming the structure, the grid, the estimate and the limit
  // when it can never fit; waits while others hold the budget, until `stop` says otherwise. Call it
  // on a worker: a reservation held while waiting for a worker could starve the workers waiting
  // for the budget (a cycle).
  Result<Admission> admit(const db::StructureRecord& structure, const ImageGeometry& geometry, const WorkExtras& extras,
                          const std::function<Status()>& stop = {});

  int64_t max_grid_voxels() const { return max_grid_voxels_; }

  // The series' stored image, decoded (cached). DATA_LOSS naming the series for a damaged blob.
  Result<std::shared_ptr<const Image>> image(const db::SeriesRecord& series);

 private:
  // convert()'s work on a decoded mesh, the admission checked by the caller.
  Result<Voxelization> convert_mesh(const db::StructureRecord& structure, const TriangleMesh& mesh,
                                    const ImageGeometry& geometry, FillRule fill_rule) const;
  // admit()'s reservation once the surface's measure is known.
  Result<Admission> reserve_for(const db::StructureRecord& structure, const ImageGeometry& geometry,
                                const WorkExtras& extras, const SurfaceMeasure& measure,
                                const std::function<Status()>& stop);

  db::Store& store_;
  const int64_t max_grid_voxels_;
  MemoryBudget& budget_;
  LruCache<TriangleMesh> surfaces_;
  LruCache<SurfaceMeasure> measures_;  // a few dozen bytes per surface: admission without a pass
  LruCache<Image> images_;
};

// "name" or "name|region|sha|interpolation".
std::string feature_entry(const std::string& name, const std::string& region, const std::string& image_sha,
                          Interpolation interpolation);

}  // namespace soiq::server
