#pragma once
// The integration tests' cohort: a configuration of the synthetic-cohort generator
// (client/cohort/synthetic_cohort.h), uploaded to a real soiqd. Patients "C01", "C02", ... with
// the generator's demographics (seed kCohortSeed), one MR study each with its blob image, and
// hippocampus and amygdala on both sides (deformed ellipsoids of about 1,600 triangles). Every file
// that is uploaded is also kept, so tests can recompute offline exactly what the server saw.

#include <cstdint>
#include <string>
#include <vector>

#include "client/cohort/synthetic_cohort.h"
#include "tests/integration/service_fixture.h"

namespace soiq::testing {

struct CohortStructure {
  int64_t id = 0;
  std::string patient, study, name, laterality, sex;
  double age = 0;          // completed years at the study, as uploaded
  std::string mesh_path;   // the uploaded files
  std::string image_path;  // its study's MR image
};

struct Cohort {
  std::vector<CohortStructure> structures;  // per patient: hippocampus L, R, amygdala L, R
};

constexpr uint64_t kCohortSeed = 4;

cohort::CohortConfig test_cohort_config();

// Uploads the first `patients` patients of the cohort, each image then its surfaces, with the age
// at the study given explicitly. Fails the test on any upload error.
Cohort load_cohort(ServiceTest& t, client::Client& c, TempDir& dir, int patients);

}  // namespace soiq::testing
