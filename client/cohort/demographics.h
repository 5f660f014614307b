#pragma once
// Plausible demographics for a synthetic patient with one study: sex, birth date, study date,
// modality and study description, drawn from ranges (DICOM DA dates, YYYYMMDD).
//
// draw_demographics, in this order of draws (so a configuration gives the same patients anywhere):
//   sex: uniform over `sexes` (no draw when there is one);
//   dates, when years_before_study_max == 0: birth year in [birth_year_min, birth_year_max], month
//     1-12, day 1-28; then the study year in [max(study_year_min, birth year + 1), study_year_max],
//     month, day. Otherwise the study date first (years as above, no birth bound), then the birth
//     year years_before_study_min..max years before it, month, day: for a planted age group;
//   modality: by the percentages of `modalities` (no draw when there is one).
// Inputs: ranges with min <= max, study_year_max > birth_year_min, percents summing to 100.
// completed_years: whole years from `birth_date` to `study_date` (the birthday counts), as used to
// age structures; the store's own age is fractional (db/age_years.h).
// Cost: O(1). Thread-safe given one generator per thread.

#include <string>
#include <vector>

#include "client/cohort/split_mix_64.h"

namespace soiq::cohort {

struct ModalityShare {
  std::string modality;           // "MR", "CT", "PT"
  std::string study_description;  // "Brain MR"
  int percent = 100;
};

struct DemographicRanges {
  std::vector<std::string> sexes = {"M", "F"};
  int birth_year_min = 1940, birth_year_max = 2000;
  int study_year_min = 2015, study_year_max = 2025;
  int years_before_study_min = 0, years_before_study_max = 0;  // 0: the birth range above is used
  std::vector<ModalityShare> modalities = {{"MR", "Synthetic brain MR", 100}};
};

struct Demographics {
  std::string sex, birth_date, study_date, modality, study_description;
};

Demographics draw_demographics(const DemographicRanges& ranges, SplitMix64& random);

int completed_years(const std::string& birth_date, const std::string& study_date);

}  // namespace soiq::cohort
