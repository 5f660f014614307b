#pragma once
// The one synthetic-cohort generator of soiq: patients with plausible demographics, one study each
// with an MR-like image, and bilateral deep-brain structures as smooth closed surfaces. `soiq
// demo-load` uploads demo_cohort_config(); the integration tests and `soiq-bench query` use their
// own configurations of the same parts (demographics.h, bilateral_structures.h, blob_image.h).
//
// synthetic_patients(config, patients, seed): patients 1..n, cheap (no mesh, no image): id
//   "<id_prefix><n>" (n zero-padded to id_digits), study uid "<uid_root>.<seed>.<n>", series uid
//   "<study uid>.1", demographics drawn from config.demographics, completed age at the study, and a
//   seed of its own for its structures and image. One generator, seeded with `seed`, draws per
//   patient its seed then its demographics (demographics.h).
// synthetic_structures(style, p): its structures (place_bilateral_structures from SplitMix64(p.seed)),
//   L then R per kind, each a closed, outward surface in LPS mm.
// synthetic_image(config, p): its image (blob_image over the same placed structures, image_phase).
// demo_cohort_config(): ids "DEMO_001", uids "2.25.<seed>.<n>"; sex M/F about half each, born
//   1940-2000, studied 2015-2025, MR "Synthetic brain MR"; hippocampus, amygdala, caudate (about
//   1,000 triangles each; the hippocampus loses 0.4 % of its volume a year after 60, so queries find
//   a trend); images of 64x64x48 voxels, background ~100, blobs 120-170 brighter.
// The same (configuration, patients, seed) gives the same cohort, byte for byte, on every machine.
// Cost: O(patients) for the patients; O(triangles) and O(voxels x structures) per patient for the
// rest, built on demand. Thread-safe.

#include <cstdint>
#include <string>
#include <vector>

#include "client/cohort/bilateral_structures.h"
#include "client/cohort/blob_image.h"
#include "client/cohort/demographics.h"
#include "core/base/image.h"
#include "core/base/triangle_mesh.h"

namespace soiq::cohort {

struct CohortConfig {
  std::string id_prefix = "DEMO_";
  int id_digits = 3;
  std::string uid_root = "2.25";
  DemographicRanges demographics;
  StructureStyle structures;
  ImageStyle image;
};

struct SyntheticPatient {
  std::string patient_id, study_uid, series_uid;
  Demographics demographics;
  int age_years = 0;  // completed years at the study
  uint64_t seed = 0;  // of its structures and image
};

struct SyntheticStructure {
  std::string name;        // "hippocampus", ...
  std::string laterality;  // "L" or "R"
  TriangleMesh surface;    // LPS mm, closed, outward
};

std::vector<SyntheticPatient> synthetic_patients(const CohortConfig& config, int patients, uint64_t seed);

std::vector<SyntheticStructure> synthetic_structures(const StructureStyle& style, const SyntheticPatient& p);

Image synthetic_image(const CohortConfig& config, const SyntheticPatient& p);

CohortConfig demo_cohort_config();

}  // namespace soiq::cohort
