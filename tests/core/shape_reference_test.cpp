// Shape features against published tables: the IBSI-1 digital phantom (consensus values and
// tolerances) and PyRadiomics' brain1 case (../shared/REFERENCE_VALUES.md).
#include <gtest/gtest.h>

#include <string>

#include "core/features/centre_of_mass_shift.h"
#include "core/features/maximum_2d_diameters.h"
#include "core/features/surface_shape.h"
#include "core/features/volume_shape.h"
#include "core/io/marching_cubes.h"
#include "core/io/read_image.h"

namespace soiq {
namespace {

std::string data(const std::string& name) { return std::string(SOIQ_TEST_DATA_DIR) + "/" + name; }

struct AllShape {
  VolumeShape volume;
  SurfaceShape surface;
  Maximum2DDiameters diameters;
};

// The IBSI / PyRadiomics pipeline for a mask: voxel features from the runs, mesh features from
// marching_cubes(mask) with the bounding box in the image's own axes.
AllShape all_shape(const Mask& mask, CovarianceDivisor divisor) {
  AllShape out;
  const auto v = volume_shape(from_mask(mask), divisor);
  EXPECT_TRUE(v.ok()) << v.status().to_string();
  const auto mesh = marching_cubes(mask);
  EXPECT_TRUE(mesh.ok()) << mesh.status().to_string();
  if (!v.ok() || !mesh.ok()) return out;
  out.volume = *v;
  const auto s = surface_shape(*mesh, mask.geometry.direction);
  EXPECT_TRUE(s.ok()) << s.status().to_string();
  const auto d = maximum_2d_diameters(*mesh, mask.geometry);
  EXPECT_TRUE(d.ok()) << d.status().to_string();
  if (s.ok()) out.surface = *s;
  if (d.ok()) out.diameters = *d;
  return out;
}

// ---- IBSI-1 digital phantom: every morphology value, value +- the consensus tolerance. ----

class IbsiPhantomShape : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto mask_image = read_image(data("ibsi_digital_phantom/mask.nii.gz"));
    const auto image = read_image(data("ibsi_digital_phantom/phantom.nii.gz"));
    ASSERT_TRUE(mask_image.ok() && image.ok());
    const Mask mask = mask_from_image(*mask_image);
    // The IBSI consensus axis lengths come from the sample covariance (N - 1; volume_shape.h).
    shape_ = new AllShape(all_shape(mask, CovarianceDivisor::kNMinus1));
    const auto shift = centre_of_mass_shift_mm(from_mask(mask), *image);
    ASSERT_TRUE(shift.ok()) << shift.status().to_string();
    shift_mm_ = *shift;
  }
  static void TearDownTestSuite() { delete shape_; }
  static AllShape* shape_;
  static double shift_mm_;
};
AllShape* IbsiPhantomShape::shape_ = nullptr;
double IbsiPhantomShape::shift_mm_ = 0;

TEST_F(IbsiPhantomShape, MeshVolumeRNU0) { EXPECT_NEAR(shape_->surface.mesh_volume_mm3, 556, 4); }
TEST_F(IbsiPhantomShape, VoxelVolumeYEKZ) { EXPECT_NEAR(shape_->volume.voxel_volume_mm3, 592, 4); }
TEST_F(IbsiPhantomShape, SurfaceAreaC0JK) { EXPECT_NEAR(shape_->surface.surface_area_mm2, 388, 3); }
TEST_F(IbsiPhantomShape, SurfaceToVolumeRatio2PR5) { EXPECT_NEAR(shape_->surface.surface_volume_ratio, 0.698, 0.004); }
TEST_F(IbsiPhantomShape, Compactness1SKGS) { EXPECT_NEAR(shape_->surface.compactness_1, 0.0411, 0.0003); }
TEST_F(IbsiPhantomShape, Compactness2BQWJ) { EXPECT_NEAR(shape_->surface.compactness_2, 0.599, 0.004); }
TEST_F(IbsiPhantomShape, SphericalDisproportionKRCK) {
  EXPECT_NEAR(shape_->surface.spherical_disproportion, 1.19, 0.01);
}
TEST_F(IbsiPhantomShape, SphericityQCFX) { EXPECT_NEAR(shape_->surface.sphericity, 0.843, 0.005); }
TEST_F(IbsiPhantomShape, Asphericity25C7) { EXPECT_NEAR(shape_->surface.asphericity, 0.186, 0.001); }
TEST_F(IbsiPhantomShape, CentreOfMassShiftKLMA) { EXPECT_NEAR(shift_mm_, 0.672, 0.004); }
TEST_F(IbsiPhantomShape, Maximum3DDiameterL0JK) { EXPECT_NEAR(shape_->surface.maximum_3d_diameter_mm, 13.1, 0.1); }
TEST_F(IbsiPhantomShape, MajorAxisLengthTDIC) { EXPECT_NEAR(shape_->volume.major_axis_length_mm, 11.4, 0.1); }
TEST_F(IbsiPhantomShape, MinorAxisLengthP9VJ) { EXPECT_NEAR(shape_->volume.minor_axis_length_mm, 9.31, 0.06); }
TEST_F(IbsiPhantomShape, LeastAxisLength7J51) { EXPECT_NEAR(shape_->volume.least_axis_length_mm, 8.54, 0.05); }
TEST_F(IbsiPhantomShape, ElongationQ3CK) { EXPECT_NEAR(shape_->volume.elongation, 0.816, 0.005); }
TEST_F(IbsiPhantomShape, FlatnessN17B) { EXPECT_NEAR(shape_->volume.flatness, 0.749, 0.005); }
TEST_F(IbsiPhantomShape, VolumeDensityAabbPBX1) { EXPECT_NEAR(shape_->surface.volume_density_aabb, 0.869, 0.005); }
TEST_F(IbsiPhantomShape, AreaDensityAabbR59B) { EXPECT_NEAR(shape_->surface.area_density_aabb, 0.866, 0.005); }
TEST_F(IbsiPhantomShape, VolumeDensityConvexHullR3ER) {
  EXPECT_NEAR(shape_->surface.volume_density_convex_hull, 0.961, 0.006);
}
TEST_F(IbsiPhantomShape, AreaDensityConvexHull7T7F) {
  EXPECT_NEAR(shape_->surface.area_density_convex_hull, 1.03, 0.01);
}

// ---- PyRadiomics brain1, label 1 on the original grid. ----
// Voxel-centre and vertex-position features to 1e-9 relative (they do not depend on how a
// marching-cubes table resolves ambiguous cubes); mesh volume, area and sphericity within 0.5 %
// (REFERENCE_VALUES.md: they do depend on it).

class PyRadiomicsBrain1Shape : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto label = read_image(data("pyradiomics/brain1_label.nrrd"));
    ASSERT_TRUE(label.ok()) << label.status().to_string();
    shape_ = new AllShape(all_shape(mask_from_image(*label, 1), CovarianceDivisor::kN));
  }
  static void TearDownTestSuite() { delete shape_; }
  static AllShape* shape_;
};
AllShape* PyRadiomicsBrain1Shape::shape_ = nullptr;

constexpr double kExact = 1e-9;  // relative
constexpr double kMesh = 0.005;  // relative

TEST_F(PyRadiomicsBrain1Shape, VoxelVolume) {
  EXPECT_NEAR(shape_->volume.voxel_volume_mm3, 16412.658691406243, kExact * 16412.658691406243);
}
TEST_F(PyRadiomicsBrain1Shape, Maximum3DDiameter) {
  EXPECT_NEAR(shape_->surface.maximum_3d_diameter_mm, 69.6009903059, kExact * 69.6009903059);
}
TEST_F(PyRadiomicsBrain1Shape, Maximum2DDiameterSlice) {
  EXPECT_NEAR(shape_->diameters.slice_mm, 53.5939777692, kExact * 53.5939777692);
}
TEST_F(PyRadiomicsBrain1Shape, Maximum2DDiameterColumn) {
  EXPECT_NEAR(shape_->diameters.column_mm, 49.4908549791, kExact * 49.4908549791);
}
TEST_F(PyRadiomicsBrain1Shape, Maximum2DDiameterRow) {
  EXPECT_NEAR(shape_->diameters.row_mm, 65.8890595172, kExact * 65.8890595172);
}
TEST_F(PyRadiomicsBrain1Shape, MajorAxisLength) {
  EXPECT_NEAR(shape_->volume.major_axis_length_mm, 61.99722046980879, kExact * 61.99722046980879);
}
TEST_F(PyRadiomicsBrain1Shape, MinorAxisLength) {
  EXPECT_NEAR(shape_->volume.minor_axis_length_mm, 34.849701666854706, kExact * 34.849701666854706);
}
TEST_F(PyRadiomicsBrain1Shape, LeastAxisLength) {
  EXPECT_NEAR(shape_->volume.least_axis_length_mm, 28.584423185376522, kExact * 28.584423185376522);
}
TEST_F(PyRadiomicsBrain1Shape, Elongation) {
  EXPECT_NEAR(shape_->volume.elongation, 0.5621171627174109, kExact * 0.5621171627174109);
}
TEST_F(PyRadiomicsBrain1Shape, Flatness) {
  EXPECT_NEAR(shape_->volume.flatness, 0.46105975346582634, kExact * 0.46105975346582634);
}
TEST_F(PyRadiomicsBrain1Shape, MeshVolume) {
  EXPECT_NEAR(shape_->surface.mesh_volume_mm3, 16149.4954427, kMesh * 16149.4954427);
}
TEST_F(PyRadiomicsBrain1Shape, SurfaceArea) {
  EXPECT_NEAR(shape_->surface.surface_area_mm2, 6433.7343171, kMesh * 6433.7343171);
}
TEST_F(PyRadiomicsBrain1Shape, Sphericity) {
  EXPECT_NEAR(shape_->surface.sphericity, 0.480242186182, kMesh * 0.480242186182);
}

}  // namespace
}  // namespace soiq
