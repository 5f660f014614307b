#include "server/app/structure_conversion.h"

#include <optional>
#include <utility>

#include "core/base/run_length_volume.h"
#include "core/io/write_image.h"
#include "server/util/temp_file.h"

namespace soiq::server {

Result<StructureConversion> convert_structure(db::Store& store, FeatureEngine& features, WorkerPool& pool,
                                              int64_t structure_id, const GridChoice& choice, FillRule fill_rule,
                                              bool mask_export, const std::function<Status()>& stop) {
  SOIQ_ASSIGN_OR_RETURN(db::StructureRecord structure, store.get_structure(structure_id));
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, store.list_series(structure.study_uid));
  SOIQ_ASSIGN_OR_RETURN(ResolvedGrid grid, resolve_grid(choice, structure, series, 0, features.max_grid_voxels()));
  // Admitted on the worker, never before: a reservation held while waiting for a worker could
  // block workers that wait for the budget.
  FeatureEngine::WorkExtras extras;
  extras.mask_export = mask_export;
  std::optional<StructureConversion> out;
  auto work = [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(FeatureEngine::Admission held, features.admit(structure, grid.geometry, extras, stop));
    SOIQ_ASSIGN_OR_RETURN(Voxelization voxelization, features.convert(held, structure, grid.geometry, fill_rule));
    out.emplace(StructureConversion{std::move(structure), std::move(grid), std::move(voxelization), std::move(held)});
    return ok_status();
  };
  SOIQ_RETURN_IF_ERROR(pool.call(work));
  return std::move(*out);
}

Result<StructureCoverage> cover_structure(db::Store& store, FeatureEngine& features, WorkerPool& pool,
                                          int64_t structure_id, const GridChoice& choice, FillRule fill_rule,
                                          int lines_per_voxel, int fraction_bytes,
                                          const std::function<Status()>& stop) {
  SOIQ_ASSIGN_OR_RETURN(db::StructureRecord structure, store.get_structure(structure_id));
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, store.list_series(structure.study_uid));
  SOIQ_ASSIGN_OR_RETURN(ResolvedGrid grid, resolve_grid(choice, structure, series, 0, features.max_grid_voxels()));
  FeatureEngine::WorkExtras extras;
  extras.coverage_lines = lines_per_voxel;
  extras.fraction_bytes = fraction_bytes;
  std::optional<StructureCoverage> out;
  auto work = [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(FeatureEngine::Admission held, features.admit(structure, grid.geometry, extras, stop));
    SOIQ_ASSIGN_OR_RETURN(CoverageVolume coverage,
                          features.cover(held, structure, grid.geometry, fill_rule, lines_per_voxel));
    out.emplace(StructureCoverage{std::move(structure), std::move(grid), std::move(coverage), std::move(held)});
    return ok_status();
  };
  SOIQ_RETURN_IF_ERROR(pool.call(work));
  return std::move(*out);
}

Result<std::string> fraction_nifti_bytes(const CoverageVolume& coverage, bool float32, int64_t max_voxels) {
  SOIQ_RETURN_IF_ERROR(check_evenly_spaced(coverage.geometry, "the fractions as NIfTI"));
  SOIQ_ASSIGN_OR_RETURN(TempFile file, TempFile::create(".nii.gz"));
  if (float32) {
    SOIQ_ASSIGN_OR_RETURN(const Image image, to_fraction_image(coverage, max_voxels));
    SOIQ_RETURN_IF_ERROR(write_image(image, file.path()));
  } else {
    SOIQ_ASSIGN_OR_RETURN(const Mask bytes, to_fraction_bytes(coverage, max_voxels));
    SOIQ_RETURN_IF_ERROR(write_mask(bytes, file.path()));
  }
  return file.read();
}

Result<std::string> mask_nifti_bytes(const RunLengthVolume& volume, int64_t max_voxels) {
  SOIQ_RETURN_IF_ERROR(check_evenly_spaced(volume.geometry, "the structure as NIfTI"));
  SOIQ_ASSIGN_OR_RETURN(const Mask mask, to_mask(volume, max_voxels));
  // libnifti writes to a path: a private temporary file, never one a client named.
  SOIQ_ASSIGN_OR_RETURN(TempFile file, TempFile::create(".nii.gz"));
  SOIQ_RETURN_IF_ERROR(write_mask(mask, file.path()));
  return file.read();
}

}  // namespace soiq::server
