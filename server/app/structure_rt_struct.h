#pragma once
// Imported structures as one DICOM RT Structure Set on the image series they were imported on
// (ExportRtStruct, PacsPush --as rtstruct, DICOMweb). Each structure's stored surface is cut by
// the series' slice planes (core/geometry/slice_sections.h), then dicom::write_rt_struct writes
// the object. Filled even-odd, the contours give back exactly the voxels the 1D method gives the
// surface on that series (for imported structures: the voxels imported), up to DS rounding
// (rt_struct_export.h: 5e-12 mm).
//
// Inputs   ids: 1..kMaxRtStructStructures distinct structure ids, all imported from DICOM on the
//          same series. series_description: "" for write_rt_struct's default. uids: the Series
//          and SOP Instance UIDs to write (DICOMweb's stable ones, structure_object_uids.h), with
//          the structure's creation time as the Structure Set Date/Time; nullptr: new ones, now.
// Output   The written RT Structure Set, ROI n = ids[n-1], named as the structure.
// Errors   as structures_on_series.h (INVALID_ARGUMENT, NOT_FOUND, FAILED_PRECONDITION);
//          DATA_LOSS for a damaged stored surface; FAILED_PRECONDITION for a surface that is not
//          closed or that meets no plane of the series; RESOURCE_EXHAUSTED when the writing does
//          not fit the memory budget. `stop` ends a wait for the budget.
// Memory   the object's bytes are reserved before writing (from the contours' point count) and
//          stay counted as long as the BudgetedRtStruct lives.
// Cost     O(T + C log C) per structure for its cuts, then O(points). Thread-safe as
//          FeatureEngine and Store are.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "dicom/rt_struct_export.h"
#include "server/app/feature_engine.h"
#include "server/app/memory_budget.h"
#include "server/app/structure_object_uids.h"

namespace soiq::server {

inline constexpr int kMaxRtStructStructures = 256;

struct BudgetedRtStruct {
  dicom::WrittenRtStruct rt_struct;
  std::string referenced_series_uid, study_uid;
  MemoryBudget::Reservation held;
};

Result<BudgetedRtStruct> structure_rt_struct(db::Store& store, FeatureEngine& features, MemoryBudget& budget,
                                             const std::vector<int64_t>& ids, const std::string& series_description,
                                             const StructureObjectUids* uids = nullptr,
                                             const std::function<Status()>& stop = {});

// The Series Description of the RT Structure Set of one structure as DICOMweb lists and writes it:
// its name when that is a valid LO value, else write_rt_struct's default.
std::string rt_struct_series_description(const std::string& structure_name);

}  // namespace soiq::server
