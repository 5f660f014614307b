#pragma once
// Imported structures as one DICOM SEG on the image series they were converted on (ExportSeg and
// PacsPush): binary by default, or FRACTIONAL (OCCUPANCY) coverage fractions when asked. Each
// structure's stored surface is converted back on that series' grid by the 1D method (lossless
// for imported structures: their surface is the marching-cubes surface of exactly that volume),
// or covered by it with oversample x oversample lines per voxel (FeatureEngine::cover), then
// dicom::write_seg or dicom::write_fractional_seg writes the object.
//
// Inputs   ids: 1..kMaxSegStructures distinct structure ids, all imported from DICOM and all
//          converted on the same series. series_description: "" for write_seg's default.
//          uids: the Series and SOP Instance UIDs to write (DICOMweb's stable ones,
//          structure_object_uids.h); nullptr: new ones. oversample: 0 a binary SEG, 1..8 a fractional
//          one (always with new UIDs, so that it and the binary SEG of the same structures can
//          both live in a PACS).
// Output   The written SEG, segment n = ids[n-1], labelled with the structure's name.
// Errors   INVALID_ARGUMENT: no ids, too many, a repeated id, oversample outside 0..8, oversample
//          with uids; NOT_FOUND: an unknown id or a series no longer stored;
//          FAILED_PRECONDITION: an uploaded structure (no DICOM images to reference: import
//          images and RT Structure Set with 'soiq import'), with oversample a structure stored in
//          robust mode (an open surface has no fractions), structures of different series, a
//          series stored without DICOM references; RESOURCE_EXHAUSTED: a grid over
//          max_grid_voxels; INVALID_ARGUMENT from write_seg (e.g. an empty structure).
// Memory   each conversion is admitted against the budget (FeatureEngine::admit, with
//          WorkExtras::coverage_lines for fractions), and once done holds only its runs (or its
//          coverage); the SEG's writing is admitted by its peak (seg_write_peak_bytes or
//          fractional_seg_write_peak_bytes, which count the frames' bytes: no dense volume is made);
//          the SEG's bytes stay counted in the budget as long as the BudgetedSeg lives (an HTTP
//          answer keeps it until written). `stop` ends a wait for the budget (CANCELLED, ...).
// Cost     one conversion per structure, then O(frames x rows x columns). Thread-safe as
//          FeatureEngine and Store are.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "dicom/seg_export.h"
#include "server/app/feature_engine.h"
#include "server/app/memory_budget.h"
#include "server/app/structure_object_uids.h"

namespace soiq::server {

inline constexpr int kMaxSegStructures = 256;

// A written SEG and its bytes' share of the memory budget, given back when it goes.
struct BudgetedSeg {
  dicom::WrittenSeg seg;
  MemoryBudget::Reservation held;
};

Result<BudgetedSeg> structure_seg(db::Store& store, FeatureEngine& features, MemoryBudget& budget,
                                  const std::vector<int64_t>& ids, const std::string& series_description,
                                  const StructureObjectUids* uids = nullptr, const std::function<Status()>& stop = {},
                                  int oversample = 0);

// The Series Description of the SEG of one structure as DICOMweb lists and writes it: its name when
// that is a valid LO value, else write_seg's default.
std::string seg_series_description(const std::string& structure_name);

}  // namespace soiq::server
