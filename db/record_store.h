#pragma once
// The records and their searches, one of the store's three roles (db/store.h): what a DICOM
// import or an upload adds and a delete removes, the reads of patients, studies, series and
// structures, DICOMweb's searches, the blobs, and stage 1 of a query (docs/DESIGN.md "Storage").
//
// The store's contract (db/store.h) holds for every method here: one transaction per write, errors
// as soiq::Status codes, safe to call from many threads at once.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/base/comparison.h"
#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "db/store_records.h"
#include "db/structure_object.h"

namespace soiq::db {

// A new structure with its surface blob. The patient and study are inserted or updated (non-empty
// fields of the given records overwrite stored ones); the blob is stored unless a blob with the
// same sha256 is already there.
struct NewStructure {
  PatientRecord patient;
  StudyRecord study;
  std::string name;
  std::string laterality;
  bool robust = false;
  SurfaceInfo surface;
  std::string surface_blob;       // encoded (db/surface_blob.h)
  std::string source_series_uid;  // see StructureRecord
  std::string source_uid;         // non-empty: replaces the structure with this source_uid, if any
  // True for a structure that may be one soiq already holds coming back (a DICOM SEG soiq
  // exported, server/app/structure_seg.h, imported again): when no structure has source_uid, a stored
  // structure of the same study with the same source_series_uid, name and surface sha256 (the
  // same voxels on the same grid) is this structure. Nothing is written for it (its source_uid
  // stays the one it was first imported with) and it is returned with `recognised`.
  bool same_content_is_same_structure = false;
  // False for DICOM (an RT Structure Set ROI or SEG segment, whose source_uid holds its SOP
  // Instance UID): a UID names one content, so a structure stored under source_uid with another
  // surface or name is ALREADY_EXISTS naming what differs, unless the caller asks to replace.
  // The same content is a no-op.
  bool replace_other_content = true;
};

struct AddedStructure {
  StructureRecord structure;
  bool surface_already_stored = false;
  bool replaced = false;    // an existing structure with the same source_uid was updated (same id)
  bool recognised = false;  // same_content_is_same_structure found it stored: nothing written
};

// One original DICOM file of a new series (InstanceRecord): record.series_uid is the series'.
struct NewInstance {
  InstanceRecord record;  // file_sha256 and file_bytes filled by the caller from `file`
  std::string file;       // the Part 10 bytes as received
};

struct NewSeries {
  PatientRecord patient;
  StudyRecord study;
  SeriesRecord series;     // sha256 filled by the caller from the blob
  std::string image_blob;  // encoded (db/image_blob.h)
  // Its original instances, or none (soiqd --keep-instances off, an upload). Each SOP Instance UID
  // must be one of series.slice_instance_uids. Stored with the series; a replaced series' instances
  // are replaced; when the series is stored with the same content already, the instances it lacks
  // are added (so importing again fills a series stored before instances were kept).
  std::vector<NewInstance> instances;
  // False for DICOM: a series stored under this uid with other voxels or other slice SOP
  // Instance UIDs is ALREADY_EXISTS naming what differs, unless the caller asks to replace; the
  // same content is a no-op.
  bool replace_other_content = true;
};

// Everything one DICOM import adds (server/app/dicom_import.h), written by import_batch in one
// transaction: either all of it is stored or, on any error, none of it.
struct ImportBatch {
  std::vector<NewSeries> series;
  std::vector<NewStructure> structures;
};

struct ImportedBatch {
  std::vector<bool> series_replaced;       // by index of ImportBatch::series
  std::vector<AddedStructure> structures;  // by index of ImportBatch::structures
};

template <typename T>
struct Page {
  std::vector<T> items;
  std::string next_page_token;  // "" on the last page
};

struct PageRequest {
  int32_t page_size = 100;  // 1..1000
  std::string page_token;
};

struct PatientFilter {
  std::string patient_id_glob;
  std::string sex;
};

struct StructureFilter {
  std::string patient_id;  // exact, or a GLOB ("DEMO_*") when it has * ? or [ in it
  std::string study_uid;
  std::string name_glob;  // case-insensitive
  std::string laterality;
};

// Precompute (docs/DESIGN.md "Queries"): soiqd computes the default features of every structure when it
// arrives, off the request path, and the store keeps the shape values among them beside the
// structure's stage-1 row, each with an index, so that stage 1 can filter the whole database on
// them. The names are the catalogue's (core/features/feature_catalogue.h) and columns of the
// store, in this order; the values are those of the feature cache's default context (soiqd's
// precompute worker computes them through it, so a query's stage 2 reads the same numbers).
inline const std::vector<std::string>& stored_feature_names() {
  static const std::vector<std::string> kNames = {"voxel_volume_mm3", "surface_area_mm2", "sphericity",
                                                  "elongation",       "flatness",         "maximum_3d_diameter_mm"};
  return kNames;
}

// `name op value` on a stored feature; op is one of < <= > >= = != (NaN and unknown never hold).
struct StoredFeatureCondition {
  std::string name;
  Comparison op = Comparison::kLess;
  double value = 0;
};

// Stage 1 of a query (docs/DESIGN.md "Queries"): all on indexed columns. Empty strings and unset
// optionals do not filter. Dates are inclusive YYYYMMDD strings.
struct Stage1Filter {
  std::string patient_id_glob;
  std::string sex;
  std::optional<double> min_age_years, max_age_years;
  std::string birth_date_from, birth_date_to;
  std::string study_date_from, study_date_to;
  std::string modality;  // the study's modality or that of one of its series
  std::string study_description_glob;
  std::string structure_name_glob;  // case-insensitive
  std::string laterality;
  // Also find each hit's contralateral twin (Candidate::twin), for asymmetry features.
  bool twins = false;
  // Conditions on the stored default features (precompute, below), all of which must hold: a
  // structure whose values are stored is kept only when they do; one whose values are not stored
  // yet (queued, or its precompute failed) is kept, for stage 2 to decide. So the caller must
  // evaluate the same conditions again in stage 2, and gets the same answer as without them.
  std::vector<StoredFeatureCondition> stored_features;
};

// One stage-1 hit: the structure with its patient and study, everything stage 2 needs to decide
// what to compute.
struct Candidate {
  StructureRecord structure;
  PatientRecord patient;
  StudyRecord study;
  // With Stage1Filter::twins: the structure of the same study with the same name (ASCII
  // case-insensitive) and the other laterality (L <-> R), the lowest id if several; whether or not
  // the filter keeps it. Never set for a structure without laterality.
  std::optional<StructureRecord> twin;
};

struct Counts {
  int64_t patients = 0, studies = 0, series = 0, structures = 0, surfaces = 0, cached_features = 0;
  int64_t instances = 0;                       // original DICOM instances kept (InstanceRecord)
  int64_t instance_files = 0;                  // distinct files they hold (by sha256)
  int64_t instance_bytes = 0;                  // those files' bytes
  int64_t precompute_queued = 0;               // structures waiting for their default features
  int64_t precompute_failed = 0;               // structures whose precompute failed (queries compute them)
  std::vector<std::string> series_modalities;  // every modality a stored series has, sorted
};

// Which blob get_blob reads: an image series' pixels (by series uid), a surface (by sha256) or an
// original DICOM instance's Part 10 file (by sha256; its sha256 is checked on every read, DATA_LOSS
// when the bytes differ).
enum class BlobKind { kImage, kSurface, kInstanceFile };

// DICOMweb's view of the store (QIDO-RS, server/http/). Its DICOM series are the image series
// imported from DICOM (those with a SOP class; an image uploaded as a file has no DICOM identity)
// and, for every structure converted on such a series, the objects soiq writes of it on demand
// (structure_object.h: its SEG, then its RT Structure Set), each one series of one instance.
// Results are in the order the store keeps (studies by when they were first stored; series by
// study, then images, then structures by id, each structure's objects together), so offset and
// limit page consistently while nothing is added or removed.
inline constexpr int64_t kMaxSearchLimit = 1000;

// Every condition given must hold; empty ones do not filter.
struct StudySearch {
  std::vector<std::string> study_uids;  // any of them
  std::string patient_id;               // exact, or a GLOB when it has * ? or [
  std::string patient_name_glob;        // a GLOB on the name, both in ASCII lower case
  // Fuzzy name matching: each word is the start of a component or word of the name (after ^ or a
  // space), ASCII case-insensitively. Globs' special characters in a word are literal.
  std::vector<std::string> patient_name_words;
  std::string study_date_from, study_date_to;  // YYYYMMDD, inclusive
  std::string accession_number;                // exact
  std::string study_id;                        // exact
  std::string modality;                        // of one of its DICOM series ("SEG", "RTSTRUCT": a structure's)
  int64_t offset = 0;                          // >= 0
  int64_t limit = 100;                         // 1..kMaxSearchLimit
};

struct StudyHit {
  StudyRecord study;
  PatientRecord patient;
  std::vector<std::string> modalities;  // of its DICOM series, sorted, each once
  int64_t series_count = 0;             // its DICOM series (a structure's objects each one)
  int64_t instance_count = 0;           // their instances (an image series': its slices)
};

struct SeriesSearch {
  std::vector<std::string> study_uids;    // any of them
  std::string patient_id;                 // exact, or a GLOB
  std::string series_uid;                 // an image series (excludes structures)
  std::optional<int64_t> structure_id;    // a structure's series (excludes image series)
  std::optional<StructureObject> object;  // only this object's series of structures (excludes images)
  std::string modality;                   // "SEG", "RTSTRUCT": that object of structures only
  int64_t offset = 0;
  int64_t limit = 100;
};

struct SeriesHit {
  StudyRecord study;
  PatientRecord patient;
  SeriesRecord series;                             // the image series; for a structure, the series it was converted on
  std::optional<StructureRecord> structure;        // set for a structure's series
  StructureObject object = StructureObject::kSeg;  // which of the structure's objects the series is
};

// What remove deletes: one structure, or a patient with all of its studies, series and structures.
struct Removal {
  enum class Kind { kStructure, kPatient } kind = Kind::kStructure;
  int64_t structure_id = 0;
  std::string patient_id;
};

// The records' role: 17 methods, each one transaction; below them, conveniences written on them
// for the common single-record cases.
class RecordStore {
 public:
  virtual ~RecordStore() = default;

  // --- writes -------------------------------------------------------------------------------
  // Each series (inserted, or replaced by uid with its image blob), then each structure (its
  // surface stored once by sha256; replaced in place by source_uid; recognised, see NewStructure),
  // all in one transaction: a refused record (FAILED_PRECONDITION for a study, series or structure
  // of another patient; INVALID_ARGUMENT for a malformed one) stores nothing.
  virtual Result<ImportedBatch> import_batch(const ImportBatch& b) = 0;
  // Deletes and returns the number of structures deleted; blobs and cached features nothing refers
  // to any more go in the same transaction. NOT_FOUND for an unknown structure or patient.
  virtual Result<int64_t> remove(const Removal& r) = 0;
  // --- reads (NOT_FOUND naming the id for an unknown one) --------------------------------------
  virtual Result<PatientRecord> get_patient(const std::string& patient_id) = 0;
  virtual Result<Page<PatientRecord>> list_patients(const PatientFilter& f, const PageRequest& p) = 0;
  virtual Result<StudyRecord> get_study(const std::string& study_uid) = 0;
  virtual Result<Page<StudyRecord>> list_studies(const std::string& patient_id, const PageRequest& p) = 0;
  virtual Result<SeriesRecord> get_series(const std::string& series_uid) = 0;
  virtual Result<std::vector<SeriesRecord>> list_series(const std::string& study_uid) = 0;
  // The series of many studies in one read (a query plans a thousand structures of a hundred
  // studies; one list_series each is a hundred transactions, each a few round trips to PostgreSQL).
  // Every study found is in the map, with an empty list when it has no series; unknown ones are not.
  virtual Result<std::map<std::string, std::vector<SeriesRecord>>> series_of_studies(
      const std::vector<std::string>& study_uids) = 0;
  virtual Result<StructureRecord> get_structure(int64_t id) = 0;
  virtual Result<Page<StructureRecord>> list_structures(const StructureFilter& f, const PageRequest& p) = 0;
  // DICOMweb's searches (above). INVALID_ARGUMENT for a negative offset, a limit outside
  // 1..kMaxSearchLimit, a malformed date or an over-long value.
  virtual Result<std::vector<StudyHit>> search_studies(const StudySearch& s) = 0;
  virtual Result<std::vector<SeriesHit>> search_series(const SeriesSearch& s) = 0;
  // An image series' blob by series uid, a surface's by sha256 (db/image_blob.h, surface_blob.h),
  // an instance file by sha256 (BlobKind).
  virtual Result<std::string> get_blob(BlobKind kind, const std::string& key) = 0;
  // The original instances kept of an image series, by slice then SOP Instance UID; empty when
  // none were kept. NOT_FOUND for an unknown series; DATA_LOSS when a metadata's checksum fails.
  virtual Result<std::vector<InstanceRecord>> list_instances(const std::string& series_uid) = 0;
  // Stage 1, ordered by structure id. More than `limit` candidates is RESOURCE_EXHAUSTED
  // (the message gives the count and says to narrow the filter).
  virtual Result<std::vector<Candidate>> stage1(const Stage1Filter& f, int64_t limit) = 0;
  virtual Result<Counts> counts() = 0;

  // --- conveniences on the methods above -----------------------------------------------------
  Result<AddedStructure> add_structure(NewStructure s) {
    ImportBatch b;
    b.structures.push_back(std::move(s));
    SOIQ_ASSIGN_OR_RETURN(ImportedBatch done, import_batch(b));
    return std::move(done.structures.at(0));
  }
  // Inserts or replaces the series (same uid) and its image blob; true when replaced.
  Result<bool> put_series(NewSeries s) {
    ImportBatch b;
    b.series.push_back(std::move(s));
    SOIQ_ASSIGN_OR_RETURN(const ImportedBatch done, import_batch(b));
    return bool(done.series_replaced.at(0));
  }
  Result<std::string> get_image_blob(const std::string& series_uid) { return get_blob(BlobKind::kImage, series_uid); }
  Result<std::string> get_surface_blob(const std::string& sha256) { return get_blob(BlobKind::kSurface, sha256); }
  Result<std::string> get_instance_file(const std::string& sha256) { return get_blob(BlobKind::kInstanceFile, sha256); }
  Result<int64_t> delete_structure(int64_t id) { return remove({Removal::Kind::kStructure, id, ""}); }
  Result<int64_t> delete_patient(const std::string& patient_id) {
    return remove({Removal::Kind::kPatient, 0, patient_id});
  }
};

}  // namespace soiq::db
