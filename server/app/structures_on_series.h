#pragma once
// The structures one DICOM export names and the image series they were imported on, as the
// writers of dicom/ take it (dicom::SegSource): the checks and look-ups every export of stored
// structures onto their images shares (the RT Structure Set export, structure_rt_struct.h).
//
// Inputs   ids: 1..max_structures distinct structure ids. object: what is being written, for
//          messages ("RT Structure Set").
// Output   The structures in the order asked and the series' source: patient, study, frame of
//          reference, slice SOP instances and grid as the import stored them.
// Errors   INVALID_ARGUMENT: no ids, too many, a repeated id, structures of different series
//          (one object references one series). NOT_FOUND: an unknown id, or the series is no
//          longer stored. FAILED_PRECONDITION: an uploaded structure (no DICOM images to
//          reference; the message says to import images and RT Structure Set with 'soiq import'),
//          a series stored without its DICOM references.
// Cost     one store read per structure and three for the series. Thread-safe as Store is.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "dicom/seg_export.h"

namespace soiq::server {

struct StructuresOnSeries {
  std::vector<db::StructureRecord> structures;
  dicom::SegSource source;
};

Result<StructuresOnSeries> structures_on_series(db::Store& store, const std::vector<int64_t>& ids, int max_structures,
                                                const std::string& object);

// "structure 7 ('GTV')"
std::string structure_named(const db::StructureRecord& s);

}  // namespace soiq::server
