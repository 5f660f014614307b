#pragma once
// Store inputs that the typed store tests and the SQLite-only tests of the same topic both use
// (the SQLite ones add a trigger, or take the file back to an older schema first).

#include <string>

#include "db/image_blob.h"
#include "db/store.h"
#include "db/surface_blob.h"
#include "tests/db/temp_store.h"

namespace soiq::db::testing {

// Two series (CT and PT) and two structures of one study: an import's usual shape.
inline ImportBatch two_series_two_structures() {
  ImportBatch b;
  b.series.push_back(new_series("P1", "S1", "SE-CT", 1.0f));
  b.series.push_back(new_series("P1", "S1", "SE-PT", 2.0f));
  b.series[1].series.modality = "PT";
  b.structures.push_back(new_structure("P1", "S1", "GTV_CT", 1.0));
  b.structures.push_back(new_structure("P1", "S1", "GTV_PT", 2.0));
  return b;
}

// A series whose study has DICOM's Study Time, Study ID and Accession Number.
inline NewSeries series_of_identified_study() {
  NewSeries s = new_series("P1", "1.2.3", "1.2.3.4", 1.0f);
  s.study.study_time = "101512.5";
  s.study.study_id = "S-17";
  s.study.accession_number = "ACC0042";
  return s;
}

// An RT Structure Set's ROI: its source series and its source uid.
inline NewStructure imported_structure(const std::string& name, double surface_offset) {
  NewStructure s = new_structure("P1", "1.2.3", name, surface_offset);
  s.source_series_uid = "1.2.3.4";
  s.source_uid = "1.2.3.77/1";
  return s;
}

// The SOP Instance UID of slice k (from 0) of a series of series_with_instances.
inline std::string slice_uid(const std::string& series_uid, int k) { return series_uid + "." + std::to_string(k + 1); }

// An original DICOM instance of slice k: its file's bytes are `file` (anything does: the store
// keeps them as they are), its metadata a JSON object naming it.
inline NewInstance instance_of(const std::string& series_uid, int k, const std::string& file) {
  NewInstance i;
  i.record.sop_instance_uid = slice_uid(series_uid, k);
  i.record.series_uid = series_uid;
  i.record.slice = k;
  i.record.file_sha256 = sha256_hex(file.data(), file.size());
  i.record.file_bytes = int64_t(file.size());
  i.record.metadata = R"({"00080018":{"vr":"UI","Value":[")" + i.record.sop_instance_uid + R"("]}})";
  i.file = file;
  return i;
}

// A file of the series' slice k, `version` telling two contents apart; with a NUL and high bytes.
inline std::string instance_file_bytes(const std::string& series_uid, int k, int version = 1) {
  return std::string("DICM\0\x80\xff", 7) + series_uid + "/" + std::to_string(k) + "/v" + std::to_string(version);
}

// A DICOM series of three slices (2x2x3 voxels of `fill`) in the patient's study "<patient>.1",
// its slice uids slice_uid(series_uid, 0..2), with its three instances (files of `version`) when
// `kept`.
inline NewSeries series_with_instances(const std::string& patient_id, const std::string& series_uid, float fill,
                                       bool kept = true, int version = 1) {
  NewSeries s = new_series(patient_id, patient_id + ".1", series_uid, fill);
  Image image;
  image.geometry = s.series.geometry;
  image.geometry.dims = {2, 2, 3};
  image.voxels.assign(12, fill);
  auto encoded = encode_image(image);
  EXPECT_TRUE(encoded.ok());
  s.series.geometry = image.geometry;
  s.series.sha256 = encoded->sha256;
  s.image_blob = encoded->blob;
  s.series.sop_class_uid = "1.2.840.10008.5.1.4.1.1.4";
  for (int k = 0; k < 3; ++k) {
    s.series.slice_instance_uids.push_back(slice_uid(series_uid, k));
    if (kept) s.instances.push_back(instance_of(series_uid, k, instance_file_bytes(series_uid, k, version)));
  }
  return s;
}

}  // namespace soiq::db::testing
