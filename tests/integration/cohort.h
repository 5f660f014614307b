#pragma once
// A small synthetic cohort for the integration tests: patients with demographics, one MR study
// each with a smooth synthetic image, and bilateral spheres of patient-dependent radii. Every file
// that is uploaded is also kept, so tests can recompute offline exactly what the server saw.

#include <string>
#include <vector>

#include "core/base/image.h"
#include "core/base/triangle_mesh.h"
#include "tests/integration/service_fixture.h"

namespace soiq::testing {

struct CohortStructure {
  int64_t id = 0;
  std::string patient, study, name, laterality, sex;
  double age = 0;
  std::string mesh_path;  // the uploaded file
};

struct Cohort {
  std::vector<CohortStructure> structures;
  std::vector<std::string> image_paths;  // one per study, index = patient index
};

// The image every study gets: 64 x 64 x 48 voxels of 2 mm around the origin, values
// 100 + x + 0.5 y + z^2 / 20 + 10 * patient (so inside and shell means differ, and differ by patient).
Image cohort_image(int patient);

// Uploads `patients` patients (ids "C00", "C01", ...; sex F for even, M for odd; age 30 + 3 i) with
// spheres "Hippocampus" L/R and "Amygdala" L/R. Fails the test on any upload error.
Cohort load_cohort(ServiceTest& t, client::Client& c, TempDir& dir, int patients);

}  // namespace soiq::testing
