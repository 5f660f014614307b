#pragma once
// Input checks of the store's records and filters, before any SQL runs: every failure is
// INVALID_ARGUMENT naming the field and the value (identifiers, never patient names).

#include <string>

#include "core/base/status.h"
#include "db/store.h"

namespace soiq::db {

// Lengths of what a client may name, in bytes: identifiers as DICOM bounds them (LO and UI are 64
// characters), names, descriptions and globs generously above any DICOM value, so that a 1 MB
// "name" is refused rather than stored, logged and echoed.
inline constexpr size_t kMaxIdBytes = 64;
inline constexpr size_t kMaxNameBytes = 256;
// A precompute failure is kept (for `soiq info` and the log) cut to this many bytes.
inline constexpr size_t kMaxPrecomputeFailureBytes = 1024;

// At most `max_bytes` bytes and no control characters (a newline in an id splits log lines and CSV
// rows). INVALID_ARGUMENT naming `what` and quoting at most 40 printable characters of the value.
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
// image sha256 and DICOM references (slice uids one per slice), a non-empty blob; the structure's
// name, laterality, surface sha256, source series and a non-empty blob.
Status validate_new_series(const NewSeries& s);
Status validate_new_structure(const NewStructure& s);
// What put_precomputed takes: the surface's sha256, one value per stored feature unless it failed,
// and a key and an entry name for each cache entry.
Status validate_precomputed(const Precomputed& p);

}  // namespace soiq::db
