#include "client/cohort/synthetic_cohort.h"

#include <cstdio>

namespace soiq::cohort {

std::vector<SyntheticPatient> synthetic_patients(const CohortConfig& config, int patients, uint64_t seed) {
  std::vector<SyntheticPatient> out;
  SplitMix64 random(seed);
  for (int n = 1; n <= patients; ++n) {
    SyntheticPatient p;
    char number[32];
    std::snprintf(number, sizeof number, "%0*d", config.id_digits, n);
    p.patient_id = config.id_prefix + number;
    p.study_uid = config.uid_root + "." + std::to_string(seed) + "." + std::to_string(n);
    p.series_uid = p.study_uid + ".1";
    p.seed = random.next();
    p.demographics = draw_demographics(config.demographics, random);
    p.age_years = completed_years(p.demographics.birth_date, p.demographics.study_date);
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<SyntheticStructure> synthetic_structures(const StructureStyle& style, const SyntheticPatient& p) {
  SplitMix64 random(p.seed);
  std::vector<SyntheticStructure> out;
  for (const PlacedStructure& s : place_bilateral_structures(style, p.demographics.sex, p.age_years, random))
    out.push_back({s.name, s.laterality, structure_surface(s)});
  return out;
}

Image synthetic_image(const CohortConfig& config, const SyntheticPatient& p) {
  SplitMix64 random(p.seed);  // the structures' draws again, so the blobs sit on the structures
  const std::vector<PlacedStructure> placed =
      place_bilateral_structures(config.structures, p.demographics.sex, p.age_years, random);
  return blob_image(config.image, placed, image_phase(p.seed));
}

CohortConfig demo_cohort_config() {
  CohortConfig c;  // the defaults are the demo's, but for the hippocampus's ageing
  c.structures.hippocampus_atrophy_per_year = 0.004;
  return c;
}

}  // namespace soiq::cohort
