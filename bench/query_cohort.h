#pragma once
// The cohort of `soiq-bench query`: many patients with realistic demographics,
// of whom exactly `matched` pass the benchmark's stage-1 filter (query_stage1_filter()), each of
// those with 5 bilateral deep-brain structures as smooth deformations of ellipsoids and one MR
// image; every other patient has one study and one structure whose surface is one of a few shared
// small blobs (the store deduplicates them), so stage 1 really filters 100,000 patients while the
// database stays small.
//
// Demographics: sex F/M about half each, birth 1930-2005, one study 2010-2025 at least a year after
// birth, modality MR 50 %, CT 35 %, PT 15 %. The matched patients are F, MR, study 2020-2023, age at
// study 61-74; a background patient that would pass the filter (with a year of margin on the age)
// is drawn again, so exactly `matched` pass. Same (sizes, seed), same cohort on every machine.
//
// Surfaces: hippocampus, amygdala, caudate, putamen, thalamus; L at x > 0 (LPS), R mirrored, with a
// few % of random asymmetry in size and position; a UV sphere of 10k-100k triangles scaled to the
// ellipsoid and deformed by a low-frequency radial perturbation (|perturbation| < 0.25, so it stays
// star-shaped: closed, outward, no self-intersection).
// Image: `image_dims` voxels of 2 mm centred on the origin; a smooth background plus a soft bright
// blob over each structure, so means inside and in a shell differ between structures.
// Cost: O(patients) for the demographics; structures and images are built on demand, per patient.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

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
  db::PatientRecord patient;
  db::StudyRecord study;  // modality set; age computed by the store
  bool matched = false;
  uint64_t seed = 0;  // of its structures and image
};

struct CohortStructure {
  std::string name;
  std::string laterality;
  TriangleMesh surface;
};

// Patients in id order ("QB000001", ...); the matched ones are spread evenly among them.
std::vector<CohortPatient> query_cohort_patients(const QueryCohortSize& size, uint64_t seed);

// The 10 structures of a matched patient, and its MR image.
std::vector<CohortStructure> matched_structures(const CohortPatient& p, const QueryCohortSize& size);
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

// The benchmark's stage-1 filter: F, MR, study date 2020-2023, age at study 60-75.
db::Stage1Filter query_stage1_filter();

}  // namespace soiq::bench
