#pragma once
// The cohort of `soiq-bench query`, a configuration of the synthetic-cohort generator
// (client/cohort/): many patients with realistic demographics, of whom exactly `matched` pass the
// benchmark's stage-1 filter (query_stage1_filter()), each of those with 5 bilateral deep-brain
// structures and one MR image; every other patient has one study and one structure whose surface
// is one of a few shared small blobs (the store deduplicates them), so stage 1 really filters
// 100,000 patients while the database stays small.
//
// Demographics: sex F/M about half each, birth 1930-2005, one study 2010-2025 at least a year after
// birth, modality MR 50 %, CT 35 %, PT 15 %. The matched patients are F, MR, study 2020-2023, age at
// study 61-74; a background patient that would pass the filter (with a year of margin on the age)
// is drawn again, so exactly `matched` pass. Same (sizes, seed), same cohort on every machine.
//
// Surfaces (matched_config().structures): hippocampus, amygdala, caudate, putamen, thalamus, L and
// R, deformed ellipsoids of min_triangles-max_triangles triangles (bilateral_structures.h).
// Image: `image_dims` voxels of 2 mm centred on the origin, background ~300, a blob 40-160 brighter
// over each structure (blob_image.h). Background blobs: the mean ellipsoid of kind blob % 5, on the
// right when blob % 10 >= 5, about 2,000 triangles.
// The generator's records become db:: records here (patient_record, study_record).
// Cost: O(patients) for the demographics; structures and images are built on demand, per patient.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "client/cohort/synthetic_cohort.h"
#include "core/base/image.h"
#include "core/base/triangle_mesh.h"
#include "db/store.h"

namespace soiq::bench {

struct QueryCohortSize {
  int patients = 100000;
  int matched = 100;
  int min_triangles = 10000;
  int max_triangles = 100000;
  int background_blobs = 8;  // distinct surfaces shared by the background patients
  std::array<int64_t, 3> image_dims = {96, 96, 72};
};

struct CohortPatient {
  cohort::SyntheticPatient person;  // ids, demographics, the seed of its structures and image
  bool matched = false;
};

// Patients in id order ("QB000001", ...); the matched ones are spread evenly among them.
std::vector<CohortPatient> query_cohort_patients(const QueryCohortSize& size, uint64_t seed);

// The generator's configuration of the matched patients' structures and image.
cohort::CohortConfig matched_config(const QueryCohortSize& size);

// The 10 structures of a matched patient, and its MR image.
std::vector<cohort::SyntheticStructure> matched_structures(const CohortPatient& p, const QueryCohortSize& size);
Image matched_image(const CohortPatient& p, const QueryCohortSize& size);

// The background patient's one structure: blob index in [0, background_blobs), name, laterality.
struct BackgroundStructure {
  int blob = 0;
  std::string name;
  std::string laterality;
};
BackgroundStructure background_structure(const CohortPatient& p, const QueryCohortSize& size);
// The surface of a shared background blob (about 2,000 triangles); blob % 10 >= 5 is on the right.
TriangleMesh background_surface(int blob);

// The patient and its study as the store keeps them (the study's age is left to the store).
db::PatientRecord patient_record(const CohortPatient& p);
db::StudyRecord study_record(const CohortPatient& p);

// The benchmark's stage-1 filter: F, MR, study date 2020-2023, age at study 60-75.
db::Stage1Filter query_stage1_filter();

}  // namespace soiq::bench
