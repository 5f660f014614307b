#pragma once
// The original DICOM files of an imported image series, ready to store beside it (soiqd
// --keep-instances, on by default): WADO-RS then serves the series from soiq alone, so a viewer
// opens it and the SEGs soiq writes resolve against the SOP Instance UIDs they reference
// (docs/DESIGN.md "DICOM and PACS" says why soiq keeps them rather than fetching them from a PACS).
//
// Inputs   series: the scanned series (its files, in the folder the import received them into);
//          slice_uids: the SOP Instance UID of each slice k of the image read from it.
// Output   one NewInstance per file whose SOP Instance UID holds a slice, with its bytes as
//          received, their sha256, the slice k it holds (its first, for a multi-frame file) and
//          its DICOM JSON metadata with kBulkDataUriPlaceholder for the Pixel Data.
// Errors   INVALID_ARGUMENT naming the file when it cannot be read or parsed again (it was read
//          once already, so this means the folder changed under the import).
// Cost     one read and one parse per file; O(bytes).

#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/record_store.h"
#include "dicom/records.h"

namespace soiq::server {

Result<std::vector<db::NewInstance>> kept_instances(const dicom::DicomSeries& series,
                                                    const std::vector<std::string>& slice_uids);

// What keeping the scan's image series' files holds at the import's peak, in bytes (for its
// memory admission).
int64_t kept_instance_bytes(const dicom::DicomScan& scan);

}  // namespace soiq::server
