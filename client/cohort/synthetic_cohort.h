#pragma once
// A small synthetic cohort a newcomer can query at once (soiq demo-load) and benchmarks can reuse:
// patients with plausible demographics, one MR study each with a synthetic image, and bilateral
// deep-brain structures as smooth closed surfaces.
//
// Inputs: the number of patients (>= 1) and a seed; the same pair gives the same cohort, byte for
// byte, on every machine (a fixed 64-bit generator, no std:: distributions).
// Output, per patient "DEMO_001", ...:
//   sex M or F (about half each), birth date 1940-2000, study date 2015-2025 (YYYYMMDD), an MR study
//   "Synthetic brain MR" with uid "2.25.<seed>.<n>", a series uid "<study uid>.1";
//   an image of 64x64x48 voxels of 2 mm (LPS, identity direction, centred on the origin) whose
//   intensity is a smooth background (~100) plus a bright blob over each structure (inside ~ 250,
//   falling off over a few mm), so mean intensities inside, in a shell and in a core differ;
//   six structures: hippocampus, amygdala and caudate, each L (x > 0, the patient's left in LPS)
//   and R, as ellipsoids of plausible size (hippocampus ~3.5 cm3, amygdala ~1.5 cm3, caudate
//   ~4 cm3), slightly deformed, placed mirror-symmetric with a few % of random asymmetry; the
//   hippocampus shrinks with age (about 0.4 % a year after 60), so queries find a trend.
// Meshes are closed and outward (core/geometry/primitives.h), about 1,000 triangles each.
// Cost: O(patients x (image voxels + triangles)); about 200k voxels per patient. Thread-safe.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/image.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

struct SyntheticStructure {
  std::string name;        // "hippocampus", "amygdala", "caudate"
  std::string laterality;  // "L" or "R"
  TriangleMesh surface;    // LPS mm, closed, outward
};

struct SyntheticPatient {
  std::string patient_id, sex, birth_date;
  std::string study_uid, study_date, study_description, modality;
  std::string series_uid;
  Image image;  // the study's MR image (float32)
  std::vector<SyntheticStructure> structures;
};

std::vector<SyntheticPatient> synthetic_cohort(int patients, uint64_t seed);

}  // namespace soiq
