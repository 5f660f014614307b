#pragma once
// What a scan of DICOM files finds (docs/DESIGN.md "DICOM and PACS"): patients, studies, series and
// their instances, as plain structs with the tags docs/DESIGN.md lists. No DCMTK type appears here, so
// db/ and server/ use these without DCMTK headers. Strings are the DICOM values with padding
// removed; "" means absent or empty. No record holds a patient's name.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::dicom {

struct DicomPatient {
  std::string patient_id;  // (0010,0020)
  std::string sex;         // (0010,0040): "M", "F", "O" or ""
  std::string birth_date;  // (0010,0030) YYYYMMDD or ""
  // (0010,0010) in UTF-8 (converted from the file's Specific Character Set), "" when absent or not
  // convertible. The importer decides whether it is kept (soiqd --keep-patient-names).
  std::string name;
};

struct DicomStudy {
  std::string study_uid;  // (0020,000D)
  std::string patient_id;
  std::string study_date;        // (0008,0020) YYYYMMDD or ""
  std::string study_time;        // (0008,0030) HHMMSS.FFFFFF or a prefix, or ""
  std::string description;       // (0008,1030)
  std::string accession_number;  // (0008,0050)
  std::string study_id;          // (0020,0010)
  // From Patient's Age (0010,1010) when present (nnnD/W/M/Y), else from the birth and study dates
  // (dicom/age_at_study.h); nullopt when neither says.
  std::optional<double> age_years;
};

struct DicomInstance {
  std::string path;              // the file as found (a DICOMDIR reference resolved against the DICOMDIR's folder)
  std::string sop_instance_uid;  // (0008,0018)
  std::string sop_class_uid;     // (0008,0016)
  std::string series_uid;
  int64_t instance_number = 0;  // (0020,0013), 0 when absent
  // (0028,0010) and (0028,0011) from the header, 0 when absent: what decoding the pixels will take
  // is known before a pixel is read.
  int64_t rows = 0, columns = 0;
};

struct DicomSeries {
  std::string series_uid;  // (0020,000E)
  std::string study_uid;
  std::string modality;                // (0008,0060): "CT", "MR", "PT", "RTSTRUCT", ...
  std::string frame_of_reference_uid;  // (0020,0052), "" for series without one
  std::string description;             // (0008,103E)
  int64_t series_number = 0;           // (0020,0011), 0 when absent
  // The first Window Center/Width (0028,1050/1051) of the first file that has both, width > 0;
  // 0 and 0 when none does.
  double window_center = 0, window_width = 0;
  std::vector<DicomInstance> instances;  // sorted by instance number, then path
};

// A file that could not be used, with the reason. The Status message names the file.
struct FileProblem {
  std::string path;
  Status status;
};

struct DicomScan {
  std::vector<DicomPatient> patients;  // sorted by patient id
  std::vector<DicomStudy> studies;     // sorted by study uid
  std::vector<DicomSeries> series;     // sorted by study uid, then series number, then uid
  int64_t files_read = 0;              // DICOM instances read (DICOMDIRs not counted)
  int64_t dicomdirs_read = 0;
  int64_t non_dicom_skipped = 0;        // files that do not look like DICOM at all
  std::vector<FileProblem> unreadable;  // DICOM files (or DICOMDIR references) that failed to load

  const DicomSeries* find_series(const std::string& series_uid) const;  // nullptr when absent
  const DicomStudy* find_study(const std::string& study_uid) const;
  const DicomPatient* find_patient(const std::string& patient_id) const;
};

}  // namespace soiq::dicom
