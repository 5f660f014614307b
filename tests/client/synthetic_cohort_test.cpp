#include "client/cohort/synthetic_cohort.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/geometry/mesh_defects.h"

namespace soiq::cohort {
namespace {

TEST(SyntheticCohort, SameSeedSameCohort) {
  const CohortConfig c = demo_cohort_config();
  const auto a = synthetic_patients(c, 3, 7), b = synthetic_patients(c, 3, 7);
  ASSERT_EQ(a.size(), 3u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].demographics.birth_date, b[i].demographics.birth_date);
    EXPECT_EQ(synthetic_image(c, a[i]).voxels, synthetic_image(c, b[i]).voxels);
    EXPECT_EQ(synthetic_structures(c.structures, a[i])[0].surface.vertices_mm,
              synthetic_structures(c.structures, b[i])[0].surface.vertices_mm);
  }
  const SyntheticPatient other = synthetic_patients(c, 1, 8)[0];
  EXPECT_NE(other.demographics.birth_date + other.demographics.study_date,
            a[0].demographics.birth_date + a[0].demographics.study_date);
}

TEST(SyntheticCohort, DemoPatientsHaveDemoIdsAndDemographicsInRange) {
  const CohortConfig c = demo_cohort_config();
  const std::vector<SyntheticPatient> cohort = synthetic_patients(c, 20, 1);
  EXPECT_EQ(cohort.front().patient_id, "DEMO_001");
  EXPECT_EQ(cohort.back().study_uid, "2.25.1.20");
  EXPECT_EQ(cohort.back().series_uid, "2.25.1.20.1");
  for (const SyntheticPatient& p : cohort) {
    const Demographics& d = p.demographics;
    EXPECT_TRUE(d.sex == "M" || d.sex == "F");
    EXPECT_GE(d.birth_date, "19400101");
    EXPECT_LE(d.birth_date, "20001231");
    EXPECT_GE(d.study_date, "20150101");
    EXPECT_LE(d.study_date, "20251231");
    EXPECT_EQ(d.modality, "MR");
    EXPECT_EQ(p.age_years, completed_years(d.birth_date, d.study_date));
  }
  EXPECT_EQ(synthetic_image(c, cohort[0]).geometry.dims, (std::array<int64_t, 3>{64, 64, 48}));
  EXPECT_EQ(synthetic_structures(c.structures, cohort[0]).size(), 6u);
}

TEST(SyntheticCohort, StructuresAreClosedOutwardAndPlausiblySized) {
  const CohortConfig c = demo_cohort_config();
  for (const SyntheticStructure& s : synthetic_structures(c.structures, synthetic_patients(c, 1, 3)[0])) {
    EXPECT_TRUE(mesh_defects(s.surface).closed()) << s.name;
    EXPECT_EQ(mesh_defects(s.surface).degenerate_triangles, 0) << s.name;
    const double v = signed_volume_mm3(s.surface);
    EXPECT_GT(v, 800) << s.name << " " << s.laterality;  // amygdala ~1.5 cm3 is the smallest
    EXPECT_LT(v, 6000) << s.name << " " << s.laterality;
    // LPS: the patient's left is +x.
    double x = 0;
    for (const Vec3& q : s.surface.vertices_mm) x += q[0];
    EXPECT_EQ(x > 0, s.laterality == "L") << s.name;
  }
}

TEST(SyntheticCohort, ImageIsBrighterInsideAStructureThanAround) {
  const CohortConfig c = demo_cohort_config();
  const Image image = synthetic_image(c, synthetic_patients(c, 1, 5)[0]);
  const ImageGeometry& g = image.geometry;
  auto at = [&](const Vec3& mm) {
    const Vec3 u = g.physical_to_index(mm);
    const int64_t i = std::llround(u[0]), j = std::llround(u[1]), k = std::llround(u[2]);
    return image.voxels[size_t(i + g.dims[0] * (j + g.dims[1] * k))];
  };
  // The amygdala L is centred near (22, -14, -20); 15 mm lateral is outside it.
  EXPECT_GT(at({22, -14, -20}), at({37, -14, -20}) + 60);
}

TEST(SyntheticCohort, PlantedAgeGroupIsDrawnFromTheStudyDate) {
  DemographicRanges r;
  r.sexes = {"F"};
  r.study_year_min = 2020;
  r.study_year_max = 2023;
  r.years_before_study_min = 62;
  r.years_before_study_max = 74;
  SplitMix64 random(11);
  for (int i = 0; i < 200; ++i) {
    const Demographics d = draw_demographics(r, random);
    EXPECT_EQ(d.sex, "F");
    const int age = completed_years(d.birth_date, d.study_date);
    EXPECT_GE(age, 61) << d.birth_date << " " << d.study_date;
    EXPECT_LE(age, 74) << d.birth_date << " " << d.study_date;
  }
}

TEST(SyntheticCohort, ModalitiesFollowTheirPercentages) {
  DemographicRanges r;
  r.modalities = {{"MR", "Brain MR", 50}, {"CT", "Head CT", 35}, {"PT", "Brain PET", 15}};
  SplitMix64 random(2);
  std::map<std::string, int> count;
  for (int i = 0; i < 10000; ++i) ++count[draw_demographics(r, random).modality];
  // Binomial standard deviations are below 50 of 10,000 draws; 4 of them is a safe margin.
  EXPECT_NEAR(count["MR"], 5000, 200);
  EXPECT_NEAR(count["CT"], 3500, 200);
  EXPECT_NEAR(count["PT"], 1500, 200);
}

TEST(SyntheticCohort, TriangleCountsStayInTheirRange) {
  StructureStyle style;
  style.kinds = 5;
  style.min_triangles = 2000;
  style.max_triangles = 4000;
  SplitMix64 random(4);
  const std::vector<PlacedStructure> placed = place_bilateral_structures(style, "F", 70, random);
  ASSERT_EQ(placed.size(), 10u);
  EXPECT_EQ(placed.back().name, "thalamus");
  for (const PlacedStructure& s : placed) {
    const TriangleMesh m = structure_surface(s);
    // uv_sphere_with_triangles rounds to a whole number of rings: within ~10 % of the request here.
    EXPECT_GE(double(m.triangles.size()), 0.9 * style.min_triangles) << s.name;
    EXPECT_LE(double(m.triangles.size()), 1.1 * style.max_triangles) << s.name;
    EXPECT_TRUE(mesh_defects(m).closed()) << s.name;
  }
}

}  // namespace
}  // namespace soiq::cohort
