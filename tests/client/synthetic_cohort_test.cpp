#include "client/cohort/synthetic_cohort.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/mesh_defects.h"

namespace soiq {
namespace {

TEST(SyntheticCohort, SameSeedSameCohort) {
  const auto a = synthetic_cohort(3, 7), b = synthetic_cohort(3, 7);
  ASSERT_EQ(a.size(), 3u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].birth_date, b[i].birth_date);
    EXPECT_EQ(a[i].image.voxels, b[i].image.voxels);
    EXPECT_EQ(a[i].structures[0].surface.vertices_mm, b[i].structures[0].surface.vertices_mm);
  }
  EXPECT_NE(synthetic_cohort(1, 8)[0].birth_date + synthetic_cohort(1, 8)[0].study_date,
            a[0].birth_date + a[0].study_date);
}

TEST(SyntheticCohort, DemographicsAreInRange) {
  for (const SyntheticPatient& p : synthetic_cohort(20, 1)) {
    EXPECT_TRUE(p.sex == "M" || p.sex == "F");
    EXPECT_GE(p.birth_date, "19400101");
    EXPECT_LE(p.birth_date, "20001231");
    EXPECT_GE(p.study_date, "20150101");
    EXPECT_LE(p.study_date, "20251231");
    EXPECT_EQ(p.modality, "MR");
    EXPECT_EQ(p.image.geometry.dims, (std::array<int64_t, 3>{64, 64, 48}));
    EXPECT_EQ(p.structures.size(), 6u);
  }
}

TEST(SyntheticCohort, StructuresAreClosedOutwardAndPlausiblySized) {
  const SyntheticPatient p = synthetic_cohort(1, 3)[0];
  for (const SyntheticStructure& s : p.structures) {
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
  const SyntheticPatient p = synthetic_cohort(1, 5)[0];
  const ImageGeometry& g = p.image.geometry;
  auto at = [&](const Vec3& mm) {
    const Vec3 u = g.physical_to_index(mm);
    const int64_t i = std::llround(u[0]), j = std::llround(u[1]), k = std::llround(u[2]);
    return p.image.voxels[size_t(i + g.dims[0] * (j + g.dims[1] * k))];
  };
  // The amygdala L is centred near (22, -14, -20); 15 mm lateral is outside it.
  EXPECT_GT(at({22, -14, -20}), at({37, -14, -20}) + 60);
}

}  // namespace
}  // namespace soiq
