#include "server/app/feature_engine.h"

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "core/features/feature_catalogue.h"
#include "core/features/structure_features.h"
#include "core/voxelize/coverage_1d.h"
#include "core/voxelize/memory_estimate.h"
#include "db/image_blob.h"
#include "db/surface_blob.h"

namespace soiq::server {
namespace {

// The names of the features that need an image on the structure's own grid: the one reason a
// planned value can be missing from a report.
std::string needing_own_grid() {
  std::string names;
  for (const FeatureDef& f : feature_catalogue())
    if (f.needs.has(FeatureNeed::kImageOnGrid)) names += (names.empty() ? "" : ", ") + std::string(f.name);
  return names;
}

}  // namespace

std::string feature_entry(const std::string& name, const std::string& region, const std::string& image_sha,
                          Interpolation interpolation) {
  if (region.empty()) return name;
  return name + "|" + region + "|" + image_sha + "|" + interpolation_name(interpolation);
}

Status complete_feature_ask(FeatureAsk& ask) {
  if (ask.names.empty()) ask.names = shape_feature_names();
  bool needs_image = false, takes_image = false;  // voxel_count takes one without needing it
  for (const std::string& n : ask.names) {
    SOIQ_RETURN_IF_ERROR(check_feature_name(n));
    needs_image = needs_image || is_intensity_only(n);
    takes_image = takes_image || find_intensity_feature(n) != nullptr;
  }
  if (needs_image && ask.images.empty())
    return invalid_argument(
        "intensity features need an image of the structure's study (a modality such as PT, "
        "or a series uid)");
  if (!takes_image && !ask.images.empty())
    return invalid_argument("images were given but no intensity feature was asked (e.g. mean, median, p90)");
  if (ask.regions.empty()) ask.regions.push_back(RegionSpec{});
  // A region asked twice is computed once (its values would share their cache entries anyway).
  std::vector<RegionSpec> unique;
  for (const RegionSpec& r : ask.regions) {
    const bool seen = std::any_of(unique.begin(), unique.end(),
                                  [&](const RegionSpec& u) { return region_name(u) == region_name(r); });
    if (!seen) unique.push_back(r);
  }
  ask.regions = std::move(unique);
  return ok_status();
}

FeatureEngine::FeatureEngine(db::Store& store, int64_t max_grid_voxels, MemoryBudget& budget,
                             int64_t cache_budget_bytes)
    : store_(store),
      max_grid_voxels_(max_grid_voxels),
      budget_(budget),
      surfaces_(cache_budget_bytes / 2, LruCache<TriangleMesh>::Keep::kOnSecondUse),
      measures_(int64_t(64) << 20),
      images_(cache_budget_bytes / 2) {}

Result<FeaturePlan> FeatureEngine::plan(const db::StructureRecord& structure,
                                        const std::vector<db::SeriesRecord>& study_series,
                                        const FeatureAsk& ask) const {
  FeaturePlan p;
  p.structure = structure;
  double widest_shell = 0;
  for (const RegionSpec& r : ask.regions) {
    if (r.kind == RegionKind::kShell) widest_shell = std::max(widest_shell, r.radius_mm);
  }
  SOIQ_ASSIGN_OR_RETURN(p.grid, resolve_grid(ask.grid, structure, study_series, widest_shell, max_grid_voxels_));
  // Each series once, under the first name it was asked by (a modality and its series uid may name
  // the same series).
  std::vector<std::string> refs;
  for (const std::string& ref : ask.images) {
    SOIQ_ASSIGN_OR_RETURN(db::SeriesRecord s, find_series(ref, study_series, structure.study_uid));
    const auto seen = std::find_if(p.images.begin(), p.images.end(),
                                   [&](const db::SeriesRecord& known) { return known.sha256 == s.sha256; });
    p.image_of_ask.push_back(size_t(seen - p.images.begin()));
    if (seen != p.images.end()) continue;
    p.images.push_back(std::move(s));
    refs.push_back(ref);
  }
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on a long chain of "literal" + string.
  p.cache_key = "v";
  for (const std::string& part : {std::to_string(feature_definitions_version()), structure.surface.sha256, p.grid.key,
                                  std::string(ask.fill_rule == FillRule::kEvenOdd ? "evenodd" : "nonzero")}) {
    p.cache_key += part;
    p.cache_key += '|';
  }
  if (structure.robust) p.cache_key += "robust";
  for (const std::string& n : ask.names) {
    // voxel_count is both: the structure's voxels, and with images each region's samples too, as
    // the library reports them.
    if (!is_intensity_only(n)) p.wants.push_back({feature_entry(n, "", "", ask.interpolation), n, "", ""});
    if (find_intensity_feature(n) == nullptr) continue;
    for (const RegionSpec& r : ask.regions) {
      for (size_t i = 0; i < refs.size(); ++i) {
        const std::string region = region_name(r);
        p.wants.push_back({feature_entry(n, region, p.images[i].sha256, ask.interpolation), n, region, refs[i]});
      }
    }
  }
  return p;
}

Result<std::shared_ptr<const TriangleMesh>> FeatureEngine::surface(const db::StructureRecord& structure) {
  const std::string& sha256 = structure.surface.sha256;
  // The loader knows only the surface: another structure of the same surface may be waiting for
  // its result (lru_cache.h), so the structure is named here, after it.
  Result<std::shared_ptr<const TriangleMesh>> mesh = surfaces_.get_or_load(
      sha256,
      [&]() -> Result<TriangleMesh> {
        SOIQ_ASSIGN_OR_RETURN(std::string blob, store_.get_surface_blob(sha256));
        SOIQ_ASSIGN_OR_RETURN(TriangleMesh decoded, db::decode_surface(blob));
        // A blob without a checksum of its own (version 2, or one the migration found damaged and
        // left) is checked against the sha256 it is stored under: slower, and only for those.
        const int version = db::surface_blob_version(blob);
        if (version < 3) {
          const std::string got = db::surface_sha256(decoded);
          if (got != sha256) {
            return data_loss("its blob (version " + std::to_string(version) +
                             ", without a checksum) decodes to a mesh of sha256 " + got);
          }
        }
        return decoded;
      },
      [](const TriangleMesh& m) {
        return int64_t(m.vertices_mm.size() * sizeof(Vec3) + m.triangles.size() * sizeof(m.triangles[0]));
      });
  if (mesh.ok() || mesh.status().code() != StatusCode::kDataLoss) return mesh;
  return data_loss("structure " + std::to_string(structure.id) + " (surface sha256 " + sha256 +
                   "): stored surface is corrupt: " + mesh.status().message() +
                   "; restore the store from a backup, or upload the surface again (an upload of the same mesh "
                   "replaces the damaged blob)");
}

Result<std::shared_ptr<const Image>> FeatureEngine::image(const db::SeriesRecord& series) {
  Result<std::shared_ptr<const Image>> image = images_.get_or_load(
      series.sha256,
      [&]() -> Result<Image> {
        SOIQ_ASSIGN_OR_RETURN(std::string blob, store_.get_image_blob(series.series_uid));
        return db::decode_image(blob, series.geometry);
      },
      [](const Image& img) { return int64_t(img.voxels.size() * sizeof(float)); });
  if (image.ok() || image.status().code() != StatusCode::kDataLoss) return image;
  return data_loss("image of series " + series.series_uid + " (sha256 " + series.sha256 +
                   "): stored image is corrupt: " + image.status().message() +
                   "; restore the store from a backup, or import the series again");
}

Result<Voxelization> FeatureEngine::convert(const Admission& admitted, const db::StructureRecord& structure,
                                            const ImageGeometry& geometry, FillRule fill_rule) {
  if (admitted.structure_id_ != structure.id || !(admitted.geometry_ == geometry))
    return internal_error("structure " + std::to_string(structure.id) +
                          " was about to be converted outside its memory admission");
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, max_grid_voxels_));
  SOIQ_ASSIGN_OR_RETURN(std::shared_ptr<const TriangleMesh> mesh, surface(structure));
  return convert_mesh(structure, *mesh, geometry, fill_rule);
}

Result<Voxelization> FeatureEngine::convert_mesh(const db::StructureRecord& structure, const TriangleMesh& mesh,
                                                 const ImageGeometry& geometry, FillRule fill_rule) const {
  VoxelizeOptions options;
  options.fill_rule = fill_rule;
  options.robust = structure.robust;
  options.max_voxels = max_grid_voxels_;
  const std::string name = "structure " + std::to_string(structure.id);
  options.name = name.c_str();
  // A surface stored without robust mode was checked closed at upload: no need to count its
  // defects again on every conversion (that costs as much as the conversion).
  if (!structure.robust) options.known_defects = MeshDefects{};
  return voxelize_1d(mesh, geometry, options);
}

Result<CoverageVolume> FeatureEngine::cover(const Admission& admitted, const db::StructureRecord& structure,
                                            const ImageGeometry& geometry, FillRule fill_rule, int lines_per_voxel) {
  if (admitted.structure_id_ != structure.id || !(admitted.geometry_ == geometry))
    return internal_error("structure " + std::to_string(structure.id) +
                          " was about to be converted outside its memory admission");
  if (structure.robust) {
    return failed_precondition("structure " + std::to_string(structure.id) +
                               " was uploaded in robust mode (its surface is open or self-intersecting): coverage "
                               "fractions need a closed surface; ask for a binary mask instead");
  }
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, max_grid_voxels_));
  SOIQ_ASSIGN_OR_RETURN(std::shared_ptr<const TriangleMesh> mesh, surface(structure));
  CoverageOptions options;
  options.lines_per_voxel = lines_per_voxel;
  options.fill_rule = fill_rule;
  options.max_voxels = max_grid_voxels_;
  const std::string name = "structure " + std::to_string(structure.id);
  options.name = name.c_str();
  options.known_defects = MeshDefects{};  // checked closed at upload
  return coverage_1d(*mesh, geometry, options);
}

Result<FeatureEngine::Admission> FeatureEngine::admit(const db::StructureRecord& structure,
                                                      const ImageGeometry& geometry, const WorkExtras& extras,
                                                      const std::function<Status()>& stop) {
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, max_grid_voxels_));
  // The store keeps each surface's measure (SurfaceInfo): admission then needs no decode. A record
  // without one (0 and 0) is measured from its mesh, once.
  const db::SurfaceInfo& info = structure.surface;
  if (info.area_bound_mm2 > 0 || info.perimeter_bound_mm > 0) {
    const SurfaceMeasure stored{info.vertex_count, info.triangle_count, info.area_bound_mm2, info.perimeter_bound_mm};
    return reserve_for(structure, geometry, extras, stored, stop);
  }
  SOIQ_ASSIGN_OR_RETURN(std::shared_ptr<const SurfaceMeasure> measure,
                        measures_.get_or_load(
                            structure.surface.sha256,
                            [&]() -> Result<SurfaceMeasure> {
                              SOIQ_ASSIGN_OR_RETURN(std::shared_ptr<const TriangleMesh> mesh, surface(structure));
                              return surface_measure(*mesh);
                            },
                            [](const SurfaceMeasure&) { return int64_t(sizeof(SurfaceMeasure)); }));
  return reserve_for(structure, geometry, extras, *measure, stop);
}

Result<FeatureEngine::Admission> FeatureEngine::reserve_for(const db::StructureRecord& structure,
                                                            const ImageGeometry& geometry, const WorkExtras& extras,
                                                            const SurfaceMeasure& measure,
                                                            const std::function<Status()>& stop) {
  // Coverage fractions alone (a fractional Convert) hold no runs; features hold both.
  const bool coverage_only = extras.coverage_lines > 0 && !extras.features;
  const ConversionEstimate conversion = coverage_only ? coverage_peak_bytes(measure, geometry, extras.coverage_lines)
                                                      : conversion_peak_bytes(measure, geometry, structure.robust);
  int64_t bytes = conversion.bytes;
  auto add = [&](int64_t more) { bytes = more > INT64_MAX - bytes ? INT64_MAX : bytes + more; };
  if (extras.features) add(features_extra_bytes(conversion, geometry, extras.image_voxels, extras.regions));
  if (extras.mask_export) add(mask_export_extra_bytes(geometry));
  if (extras.fraction_bytes > 0) add(fraction_export_extra_bytes(geometry, extras.fraction_bytes));
  if (extras.coverage_lines > 0 && extras.features) {
    add(coverage_peak_bytes(measure, geometry, extras.coverage_lines).bytes);
    // Each covered voxel's value and weight, per image sampled (one image at a time).
    if (extras.image_voxels > 0) add(16 * covered_voxels_bound(measure, geometry));
  }
  add(std::max<int64_t>(0, extras.other_bytes));
  const auto& d = geometry.dims;
  SOIQ_ASSIGN_OR_RETURN(
      MemoryBudget::Reservation held,
      budget_.reserve(bytes,
                      "structure " + std::to_string(structure.id) + " on a grid of " + std::to_string(d[0]) + "x" +
                          std::to_string(d[1]) + "x" + std::to_string(d[2]) + " voxels (" +
                          std::to_string(conversion.lines) + " row lines)",
                      stop));
  return Admission(std::move(held), structure.id, geometry);
}

Result<FeatureValues> FeatureEngine::compute(const FeaturePlan& plan, const FeatureAsk& ask,
                                             const std::atomic<bool>* cancelled, db::SurfaceFeatures* to_store) {
  auto check_cancel = [&]() -> Status {
    if (cancelled && cancelled->load()) return Status(StatusCode::kCancelled, "cancelled");
    return ok_status();
  };
  SOIQ_RETURN_IF_ERROR(check_cancel());
  WorkExtras extras;
  extras.features = true;
  for (const db::SeriesRecord& s : plan.images) extras.image_voxels += s.geometry.voxel_count();
  extras.regions = plan.images.empty() ? 0 : int(ask.regions.size());
  const bool weighted = std::any_of(ask.names.begin(), ask.names.end(), [](const std::string& n) {
    const auto& w = weighted_feature_names();
    return std::find(w.begin(), w.end(), n) != w.end();
  });
  if (weighted) extras.coverage_lines = kWeightedFeatureLines;
  SOIQ_ASSIGN_OR_RETURN(const Admission admitted, admit(plan.structure, plan.grid.geometry, extras, check_cancel));
  // One decode serves the conversion and the surface features: the surface cache keeps a mesh only
  // on its second use (lru_cache.h), so asking twice here would decode twice. admit() checked the
  // grid's size.
  SOIQ_ASSIGN_OR_RETURN(std::shared_ptr<const TriangleMesh> mesh, surface(plan.structure));
  SOIQ_ASSIGN_OR_RETURN(Voxelization v, convert_mesh(plan.structure, *mesh, plan.grid.geometry, ask.fill_rule));
  SOIQ_RETURN_IF_ERROR(check_cancel());

  // structure_features computes the convex hull only for the features that read it. Every stored
  // structure has a surface: the mesh is passed (no copy otherwise) whenever a surface value of it,
  // or of its mask beside it, is asked.
  FeatureRequest request;
  request.names = ask.names;
  // Empty names ask structure_features for everything: ask for a cheap one instead.
  if (request.names.empty()) request.names.emplace_back(cheapest_feature().name);
  const bool core_needs_mesh =
      weighted || std::any_of(request.names.begin(), request.names.end(), [](const std::string& n) {
        return find_feature(FeatureFamily::kSurface, n) != nullptr || mask_feature(n) != nullptr;
      });
  request.fill_rule = ask.fill_rule;

  std::vector<std::shared_ptr<const Image>> images;
  request.regions = ask.regions;
  request.interpolation = ask.interpolation;
  for (const db::SeriesRecord& s : plan.images) {
    Result<std::shared_ptr<const Image>> img = image(s);
    if (!img.ok()) {
      return Status(img.status().code(),
                    "structure " + std::to_string(plan.structure.id) + ": " + img.status().message());
    }
    images.push_back(*img);
    request.images.push_back(NamedImage{s.sha256, img->get()});
  }
  StructureInput input{std::move(v.volume), core_needs_mesh ? mesh : nullptr};
  Result<FeatureReport> report = structure_features(input, request);
  if (!report.ok()) {
    return Status(report.status().code(),
                  "structure " + std::to_string(plan.structure.id) + ": " + report.status().message());
  }
  FeatureValues values;
  std::vector<db::CachedFeature> entries;
  for (const Feature& f : report->features) {
    const std::string entry = feature_entry(f.name, f.region, f.image, ask.interpolation);
    values[entry] = f.value;
    entries.push_back({plan.cache_key, entry, f.value});
  }
  for (const WantedValue& w : plan.wants) {
    if (!values.count(w.entry))
      return failed_precondition("structure " + std::to_string(plan.structure.id) + ": feature " + w.name +
                                 (w.region.empty() ? "" : " on " + w.region + " of " + w.image) +
                                 " is not available here (" + needing_own_grid() +
                                 " needs an image on the structure's own grid)");
  }
  if (to_store != nullptr) {
    *to_store = {plan.structure.surface.sha256, std::move(entries)};
  } else {
    SOIQ_RETURN_IF_ERROR(store_.put_cached_features(plan.structure.surface.sha256, entries));
  }
  return values;
}

}  // namespace soiq::server
