#pragma once
// The safety check before a structure set or SEG is converted on a series the caller already
// holds (dicom/import_dicom.h, FindKnownSeries) instead of one sent with it: same patient, same
// frame of reference. A series uid is unique, but a file naming the wrong one, or an id mix-up
// between systems, must not put one patient's tumour on another patient's images.
//
// Inputs   who: the file, for the message ("RT Structure Set 'x'"). patient_id: the file's
//          (0010,0020), "" when absent. frames_of_reference: the file's frame of reference uids
//          (an RT Structure Set may list several), empty when absent. held: the known series.
// Output   OK when every given value matches: the patient id equals held.patient_id, and one of
//          the frames of reference equals held.frame_of_reference_uid (absent values are not
//          compared).
// Errors   INVALID_ARGUMENT naming both patients, or both frames of reference.

#include <string>
#include <vector>

#include "core/base/status.h"
#include "dicom/import_dicom.h"

namespace soiq::dicom {

Status check_same_patient_and_frame(const std::string& who, const std::string& patient_id,
                                    const std::vector<std::string>& frames_of_reference, const KnownSeries& held);

}  // namespace soiq::dicom
