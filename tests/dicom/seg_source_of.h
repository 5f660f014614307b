#pragma once
// Test support: the SegSource (dicom/seg_export.h) of an imported image series, filled from the
// scan's records the way soiqd fills it from its store. Header-only (tests/dicom globs *_test.cpp).

#include <gtest/gtest.h>

#include <string>

#include "dicom/import_dicom.h"
#include "dicom/seg_export.h"

namespace soiq::dicom::testing {

inline Result<SegSource> seg_source_of(const DicomImport& imported, const std::string& series_uid) {
  const SeriesImage* image = imported.find_image(series_uid);
  const DicomSeries* series = imported.scan.find_series(series_uid);
  const DicomStudy* study = series ? imported.scan.find_study(series->study_uid) : nullptr;
  const DicomPatient* patient = study ? imported.scan.find_patient(study->patient_id) : nullptr;
  if (!image || !patient) return not_found("series " + series_uid + " was not imported with its study and patient");
  SegSource source;
  source.patient_id = patient->patient_id;
  source.patient_sex = patient->sex;
  source.patient_birth_date = patient->birth_date;
  source.study_uid = study->study_uid;
  source.study_date = study->study_date;
  source.study_time = study->study_time;
  source.study_id = study->study_id;
  source.accession_number = study->accession_number;
  source.series_uid = series->series_uid;
  source.frame_of_reference_uid = series->frame_of_reference_uid;
  source.modality = series->modality;
  source.sop_class_uid = series->instances.at(0).sop_class_uid;
  source.slice_sop_instance_uids = image->slice_sop_instance_uids;
  source.geometry = image->image.geometry;
  return source;
}

}  // namespace soiq::dicom::testing
