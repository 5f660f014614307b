#pragma once
// Which scanned image series an RT Structure Set was drawn on (a missing referenced
// series is an error that names it, never a silent guess).
//
// Inputs   rs: from read_rt_struct; scan: the scan that holds the candidate image series.
// Output   The uid of the series to convert on, found by, in order:
//            1. an RT Referenced Series uid (Referenced Frame of Reference Sequence -> RT
//               Referenced Study -> RT Referenced Series) that the scan holds;
//            2. the series holding the most of the Contour Image Sequence's SOP instance uids;
//            3. when the file references nothing at all, the one image series of the scan that
//               shares the structure set's Frame of Reference UID.
// Errors   NOT_FOUND naming the uid(s) the structure set references (series uid, or instance
//          uids when it names no series) when none of them is in the scan, or "references no
//          image series" with the frame of reference when nothing matches; the message says to
//          import the referenced series with the structure set.
// Cost     O(instances in the scan); thread-safe.

#include <string>

#include "core/base/status.h"
#include "dicom/read_rt_struct.h"
#include "dicom/records.h"

namespace soiq::dicom {

Result<std::string> referenced_series(const RtStructureSet& rs, const DicomScan& scan);

}  // namespace soiq::dicom
