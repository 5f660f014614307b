#include "client/cohort/demographics.h"

#include <algorithm>
#include <cstdio>

namespace soiq::cohort {
namespace {

// Days 1-28 only: every month has them, so no date is ever invalid. Month, then day, in separate
// statements: the arguments of one call have no evaluation order, so inline draws differ by compiler.
std::string draw_date(int year, SplitMix64& random) {
  const int month = random.integer(1, 12);
  const int day = random.integer(1, 28);
  char text[16];
  std::snprintf(text, sizeof text, "%04d%02d%02d", year, month, day);
  return text;
}

}  // namespace

Demographics draw_demographics(const DemographicRanges& r, SplitMix64& random) {
  Demographics d;
  d.sex = r.sexes.size() == 1 ? r.sexes[0] : r.sexes[size_t(random.next() % r.sexes.size())];
  if (r.years_before_study_max == 0) {
    const int birth_year = random.integer(r.birth_year_min, r.birth_year_max);
    d.birth_date = draw_date(birth_year, random);
    d.study_date = draw_date(random.integer(std::max(r.study_year_min, birth_year + 1), r.study_year_max), random);
  } else {
    const int study_year = random.integer(r.study_year_min, r.study_year_max);
    d.study_date = draw_date(study_year, random);
    d.birth_date = draw_date(study_year - random.integer(r.years_before_study_min, r.years_before_study_max), random);
  }
  const ModalityShare* m = &r.modalities.back();
  if (r.modalities.size() > 1) {
    int left = random.integer(0, 99);
    for (const ModalityShare& share : r.modalities) {
      if (left < share.percent) {
        m = &share;
        break;
      }
      left -= share.percent;
    }
  }
  d.modality = m->modality;
  d.study_description = m->study_description;
  return d;
}

int completed_years(const std::string& birth_date, const std::string& study_date) {
  const int b = std::stoi(birth_date), s = std::stoi(study_date);
  return (s / 10000 - b / 10000) - ((s % 10000) < (b % 10000) ? 1 : 0);
}

}  // namespace soiq::cohort
