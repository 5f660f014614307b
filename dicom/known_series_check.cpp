#include "dicom/known_series_check.h"

#include <algorithm>

namespace soiq::dicom {

Status check_same_patient_and_frame(const std::string& who, const std::string& patient_id,
                                    const std::vector<std::string>& frames_of_reference, const KnownSeries& held) {
  if (!patient_id.empty() && !held.patient_id.empty() && patient_id != held.patient_id)
    return invalid_argument(who + " is of patient '" + patient_id + "' but the series " + held.series_uid +
                            " it references is stored for patient '" + held.patient_id + "'; not imported");
  if (!frames_of_reference.empty() && !held.frame_of_reference_uid.empty() &&
      std::find(frames_of_reference.begin(), frames_of_reference.end(), held.frame_of_reference_uid) ==
          frames_of_reference.end())
    return invalid_argument(who + " is in frame of reference " + frames_of_reference.front() + " but the series " +
                            held.series_uid + " it references is in " + held.frame_of_reference_uid + "; not imported");
  return ok_status();
}

}  // namespace soiq::dicom
