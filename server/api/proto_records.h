#pragma once
// Conversions between the store's records (db/store.h) and the API's messages (soiq.proto), in
// one place so every handler speaks the same dialect.

#include "core/base/field_rules.h"
#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/features/feature_catalogue.h"
#include "db/store.h"
#include "server/app/dicom_import.h"
#include "server/app/pacs_pull_studies.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

v1::Patient to_proto(const db::PatientRecord& r);
v1::Study to_proto(const db::StudyRecord& r);
v1::Series to_proto(const db::SeriesRecord& r);
v1::Structure to_proto(const db::StructureRecord& r);
v1::ImageGeometry to_proto(const ImageGeometry& g);
// ImportDicom's reply (PacsPull's last event too); bytes_received is the handler's to set.
v1::ImportDicomResponse to_proto(const DicomImportResult& r);
v1::PacsPullProgress to_proto(const PullProgress& p);
// One catalogue entry as GetServerInfo lists it.
v1::FeatureInfo to_proto(const FeatureDef& f);

// Validates what a client sent, each field by its one rule (core/base/field_rules.h): required
// ids, sex, dates, ages, texts. INVALID_ARGUMENT in the field's path ("patient.birth_date").
Result<db::PatientRecord> from_proto(const v1::Patient& p);
Result<db::StudyRecord> from_proto(const v1::Study& s, const std::string& patient_id);
// Proto3 enums are open: a client may send any number, which would otherwise fall silently into a
// default branch. INVALID_ARGUMENT naming the field and the value.
Status check_enum(int value, bool (*is_valid)(int), const char* field);

}  // namespace soiq::server
