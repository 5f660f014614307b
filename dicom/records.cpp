#include "dicom/records.h"

namespace soiq::dicom {

const DicomSeries* DicomScan::find_series(const std::string& uid) const {
  for (const auto& s : series)
    if (s.series_uid == uid) return &s;
  return nullptr;
}

const DicomStudy* DicomScan::find_study(const std::string& uid) const {
  for (const auto& s : studies)
    if (s.study_uid == uid) return &s;
  return nullptr;
}

const DicomPatient* DicomScan::find_patient(const std::string& id) const {
  for (const auto& p : patients)
    if (p.patient_id == id) return &p;
  return nullptr;
}

}  // namespace soiq::dicom
