#include "bench/query_cohort.h"

#include <algorithm>
#include <cstdio>

#include "db/age_years.h"

namespace soiq::bench {
namespace {

cohort::DemographicRanges background_ranges() {
  cohort::DemographicRanges r;
  r.birth_year_min = 1930;
  r.birth_year_max = 2005;
  r.study_year_min = 2010;
  r.study_year_max = 2025;
  r.modalities = {{"MR", "Brain MR", 50}, {"CT", "Head CT", 35}, {"PT", "Brain PET", 15}};
  return r;
}

// Born 62-74 years before the study year, on a day that keeps the age at study within [61, 75).
cohort::DemographicRanges matched_ranges() {
  cohort::DemographicRanges r;
  r.sexes = {"F"};
  r.study_year_min = 2020;
  r.study_year_max = 2023;
  r.years_before_study_min = 62;
  r.years_before_study_max = 74;
  r.modalities = {{"MR", "Brain MR", 100}};
  return r;
}

// Passes the filter, with a year of margin on the age so rounding can never decide.
bool near_filter(const cohort::Demographics& d) {
  const Result<std::optional<double>> a = db::age_years(d.birth_date, d.study_date);
  const double age = a.ok() && a->has_value() ? **a : -1;
  return d.sex == "F" && d.modality == "MR" && d.study_date >= "20200101" && d.study_date <= "20231231" && age >= 59 &&
         age <= 76;
}

}  // namespace

std::vector<CohortPatient> query_cohort_patients(const QueryCohortSize& size, uint64_t seed) {
  std::vector<CohortPatient> out(size_t(size.patients));
  cohort::SplitMix64 random(seed);
  const cohort::DemographicRanges background = background_ranges(), matched_group = matched_ranges();
  const int matched = std::min(size.matched, size.patients);
  for (int n = 0; n < size.patients; ++n) {
    CohortPatient& p = out[size_t(n)];
    cohort::SyntheticPatient& q = p.person;
    char id[32];
    std::snprintf(id, sizeof id, "QB%06d", n + 1);
    q.patient_id = id;
    q.study_uid = "2.25.4242." + std::to_string(seed) + "." + std::to_string(n + 1);
    q.series_uid = q.study_uid + ".1";
    q.seed = random.next();
    // Evenly spread: patient n is matched when it starts a new 1/matched of the list.
    p.matched = matched > 0 && (int64_t(n) * matched / size.patients) != (int64_t(n + 1) * matched / size.patients);
    if (p.matched) {
      q.demographics = draw_demographics(matched_group, random);
    } else {
      do q.demographics = draw_demographics(background, random);
      while (near_filter(q.demographics));
    }
    q.age_years = cohort::completed_years(q.demographics.birth_date, q.demographics.study_date);
  }
  return out;
}

cohort::CohortConfig matched_config(const QueryCohortSize& size) {
  cohort::CohortConfig c;
  c.structures.kinds = 5;
  c.structures.min_triangles = size.min_triangles;
  c.structures.max_triangles = size.max_triangles;
  c.structures.blob_brightness_min = 40;
  c.structures.blob_brightness_max = 160;
  c.image.dims = size.image_dims;
  c.image.background = 300;
  c.image.ripple = 40;
  return c;
}

std::vector<cohort::SyntheticStructure> matched_structures(const CohortPatient& p, const QueryCohortSize& size) {
  return cohort::synthetic_structures(matched_config(size).structures, p.person);
}

Image matched_image(const CohortPatient& p, const QueryCohortSize& size) {
  return cohort::synthetic_image(matched_config(size), p.person);
}

BackgroundStructure background_structure(const CohortPatient& p, const QueryCohortSize& size) {
  cohort::SplitMix64 random(p.person.seed);
  const int blob = random.integer(0, std::max(1, size.background_blobs) - 1);
  const std::span<const cohort::Anatomy> anatomy = cohort::deep_brain_anatomy();
  return {blob, anatomy[size_t(blob) % anatomy.size()].name, blob % 10 < 5 ? "L" : "R"};
}

TriangleMesh background_surface(int blob) {
  const std::span<const cohort::Anatomy> anatomy = cohort::deep_brain_anatomy();
  const cohort::Anatomy& a = anatomy[size_t(blob) % anatomy.size()];
  cohort::Ellipsoid where{a.left_centre_mm, a.semi_axes_mm};
  if (blob % 10 >= 5) where.centre_mm[0] = -where.centre_mm[0];  // the right side
  cohort::SplitMix64 random(uint64_t(blob) * 7919 + 1);
  return cohort::deformed_ellipsoid(where, cohort::draw_radial_bump(random), 2000);
}

db::PatientRecord patient_record(const CohortPatient& p) {
  db::PatientRecord r;
  r.patient_id = p.person.patient_id;
  r.sex = p.person.demographics.sex;
  r.birth_date = p.person.demographics.birth_date;
  return r;
}

db::StudyRecord study_record(const CohortPatient& p) {
  db::StudyRecord r;
  r.study_uid = p.person.study_uid;
  r.patient_id = p.person.patient_id;
  r.study_date = p.person.demographics.study_date;
  r.description = p.person.demographics.study_description;
  r.modality = p.person.demographics.modality;
  return r;
}

db::Stage1Filter query_stage1_filter() {
  db::Stage1Filter f;
  f.sex = "F";
  f.modality = "MR";
  f.study_date_from = "20200101";
  f.study_date_to = "20231231";
  f.min_age_years = 60;
  f.max_age_years = 75;
  return f;
}

}  // namespace soiq::bench
