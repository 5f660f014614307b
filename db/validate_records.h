#pragma once
// Input checks of the store's records and filters, before any SQL runs, by the one rule of each
// field (core/base/field_rules.h), so that both backends hold exactly the same values: every
// failure is INVALID_ARGUMENT naming the field and the value (identifiers, never patient names).

#include <string>

#include "core/base/field_rules.h"
#include "core/base/status.h"
#include "db/store.h"

namespace soiq::db {

// The lengths a client may name: the field rules' (core/base/field_rules.h).
using soiq::kMaxIdBytes;
using soiq::kMaxNameBytes;
// A precompute failure is kept (for `soiq info` and the log) cut to this many bytes.
inline constexpr size_t kMaxPrecomputeFailureBytes = 1024;

// check_text (UTF-8, no control characters, at most `max_bytes`), the error in the field `what`.
Status validate_text(const std::string& value, const std::string& what, size_t max_bytes);

Status validate_sex(const std::string& sex);                                 // "", "M", "F", "O"
Status validate_laterality(const std::string& laterality);                   // "", "L", "R"
Status validate_sha256(const std::string& sha256, const std::string& what);  // 64 lower-case hex
// "" or a DICOM UID: at most 64 characters, digits and '.' only.
Status validate_uid(const std::string& uid, const std::string& what);
// patient_id non-empty, validate_text within kMaxIdBytes; sex; birth date.
Status validate_patient(const PatientRecord& p);
// study_uid non-empty and within kMaxIdBytes, description within kMaxNameBytes; modality, study time, study id and
// accession number within kMaxIdBytes; study date; age finite and >= 0 when given; patient_id "" or `patient_id`.
Status validate_study(const StudyRecord& s, const std::string& patient_id);
// Sex, laterality, dates; ages finite and min <= max; globs and modality as validate_text.
Status validate_stage1_filter(const Stage1Filter& f);
Status validate_patient_filter(const PatientFilter& f);
Status validate_structure_filter(const StructureFilter& f);
// A surface's feature-cache entries: the surface's sha256, and a key and an entry name for each.
Status validate_cache_entries(const std::string& surface_sha256, const std::vector<CachedFeature>& entries);
// What import_batch takes: the patient and study as above, the series' uid, modality, geometry,
// image sha256 and DICOM references (slice uids one per slice), a non-empty blob, each instance
// (NewInstance: one of the slice uids, once, of this series, a slice of it, a non-empty file of the
// given size and sha256, metadata a JSON object); the structure's
// name, laterality, surface sha256, source series and a non-empty blob.
Status validate_new_series(const NewSeries& s);
Status validate_new_structure(const NewStructure& s);
// What put_precomputed takes: the surface's sha256, one value per stored feature unless it failed,
// and a key and an entry name for each cache entry.
Status validate_precomputed(const Precomputed& p);

}  // namespace soiq::db
