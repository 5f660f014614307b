// RT Structure Set ROIs -> volumes and surfaces: holes, keyholes, oblique grids, skipped ROIs.
#include "dicom/convert_rt_struct.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dicom/import_dicom.h"
#include "dicom/read_rt_struct.h"
#include "dicom_test_support.h"
#include "rt_struct_writer.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;

// 12 x 12 x 3 voxels of 1 mm, rotated by `angle` about the LPS z axis (angle 0: axis-aligned).
ImageGeometry grid(double angle = 0) {
  ImageGeometry g;
  g.dims = {12, 12, 3};
  g.origin_mm = {-3, 4, 10};
  const double c = std::cos(angle), s = std::sin(angle);
  g.direction = {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  return g;
}

// A square in index space (x, y in [a, b], slice k), as LPS points on `g`, counter-clockwise.
std::vector<Vec3> square(const ImageGeometry& g, double a, double b, double k, bool clockwise = false) {
  std::vector<Vec3> p = {g.index_to_physical({a, a, k}), g.index_to_physical({b, a, k}), g.index_to_physical({b, b, k}),
                         g.index_to_physical({a, b, k})};
  if (clockwise) std::swap(p[1], p[3]);
  return p;
}

Result<ConvertedStructureSet> write_and_convert(const std::vector<std::vector<Vec3>>& contours,
                                                const ImageGeometry& g) {
  testing::TempDir dir;
  const std::string path = dir.file("rs.dcm");
  testing::write_rt_struct(path, "ring", contours);
  auto rs = read_rt_struct(path);
  if (!rs.ok()) return rs.status();
  return convert_rt_struct(*rs, g);
}

TEST(ConvertRtStruct, InnerContourOnTheSameSliceStaysAHole) {
  // Outer square: centres 1..8 (64 voxels); inner: centres 3..5 (9 voxels), either orientation.
  for (bool clockwise : {false, true}) {
    auto r = write_and_convert({square(grid(), 0.5, 8.5, 1), square(grid(), 2.5, 5.5, 1, clockwise)}, grid());
    ASSERT_TRUE(r.ok()) << r.status().to_string();
    ASSERT_EQ(r->structures.size(), 1u);
    const ImportedStructure& s = r->structures[0];
    EXPECT_EQ(s.name, "ring");
    EXPECT_EQ(s.roi_number, 7);
    EXPECT_EQ(s.contour_count, 2);
    EXPECT_EQ(voxel_count(s.volume), 64 - 9);
    auto mask = to_mask(s.volume);
    ASSERT_TRUE(mask.ok());
    EXPECT_EQ(mask->voxels[4 + 12 * (4 + 12 * 1)], 0) << "the hole's centre must stay empty";
    EXPECT_EQ(mask->voxels[1 + 12 * (1 + 12 * 1)], 1);
    EXPECT_FALSE(s.surface.triangles.empty());
  }
}

TEST(ConvertRtStruct, KeyholeContourKeepsItsHole) {
  const ImageGeometry g = grid();
  const auto at = [&](double x, double y) { return g.index_to_physical({x, y, 2}); };
  // Outer square, a cut at y = 4.25 into the hole, around the hole, back out along the cut.
  const std::vector<Vec3> keyhole = {at(0.5, 0.5),  at(8.5, 0.5),  at(8.5, 4.25), at(5.5, 4.25),
                                     at(5.5, 5.5),  at(2.5, 5.5),  at(2.5, 2.5),  at(5.5, 2.5),
                                     at(5.5, 4.25), at(8.5, 4.25), at(8.5, 8.5),  at(0.5, 8.5)};
  auto r = write_and_convert({keyhole}, g);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(voxel_count(r->structures[0].volume), 64 - 9);
}

TEST(ConvertRtStruct, ObliqueSeriesGivesTheSameVoxelsAsAnAxisAlignedOne) {
  const ImageGeometry oblique = grid(0.5);
  auto r = write_and_convert({square(oblique, 0.5, 8.5, 0), square(oblique, 2.5, 5.5, 0)}, oblique);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(voxel_count(r->structures[0].volume), 64 - 9);
}

TEST(ConvertRtStruct, AContourMidwayBetweenSlicesLeavesOutItsRoiOnlyNamingTheContourAndDistance) {
  auto r = write_and_convert({square(grid(), 0.5, 8.5, 1.5)}, grid());
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_TRUE(r->structures.empty());
  ASSERT_EQ(r->skipped.size(), 1u);
  EXPECT_EQ(r->skipped[0].roi_number, 7);
  EXPECT_EQ(r->skipped[0].name, "ring");
  EXPECT_NE(r->skipped[0].reason.find("refused: contour 0 lies 0.5 mm from the nearest image plane"), std::string::npos)
      << r->skipped[0].reason;
}

TEST(ConvertRtStruct, AContourACoupleOfTenthsOfASpacingOffGoesToTheNearestSlice) {
  auto off = write_and_convert({square(grid(), 0.5, 8.5, 1.3)}, grid());
  auto on = write_and_convert({square(grid(), 0.5, 8.5, 1)}, grid());
  ASSERT_TRUE(off.ok() && on.ok());
  ASSERT_EQ(off->structures.size(), 1u);
  EXPECT_EQ(off->structures[0].volume.runs, on->structures[0].volume.runs);
  EXPECT_GT(voxel_count(off->structures[0].volume), 0);
}

TEST(ConvertRtStruct, PointRoisAreReportedAndSkipped) {
  auto rs = read_rt_struct(data_dir("dicom/rtstruct.dcm"));
  ASSERT_TRUE(rs.ok());
  // A 2 mm grid over the 'patient' contours' extent, slices at z = -200, -190, -180.
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  for (const auto& c : rs->rois[0].contours)
    for (const auto& p : c.points_mm)
      for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  ImageGeometry g;
  g.origin_mm = {lo[0] - 3, lo[1] - 3, -200};
  g.spacing_mm = {2, 2, 10};
  g.dims = {static_cast<int64_t>((hi[0] - lo[0]) / 2) + 4, static_cast<int64_t>((hi[1] - lo[1]) / 2) + 4, 3};
  auto r = convert_rt_struct(*rs, g);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  ASSERT_EQ(r->structures.size(), 1u);
  EXPECT_EQ(r->structures[0].name, "patient");
  // Each slice's contour encloses 120000 mm2 = 30000 voxels of 4 mm2; the boundary voxels make
  // the count differ by at most the perimeter in voxels (< 1%).
  EXPECT_NEAR(static_cast<double>(voxel_count(r->structures[0].volume)), 3 * 30000.0, 0.01 * 3 * 30000);
  ASSERT_EQ(r->skipped.size(), 2u);
  EXPECT_EQ(r->skipped[0].name, "Isocenter 1");
  EXPECT_NE(r->skipped[0].reason.find("POINT"), std::string::npos) << r->skipped[0].reason;
}

TEST(ConvertRtStruct, RtUtilsStructureSetsConvertOnTheirCt) {
  auto imported = import_dicom({data_dir("dicom/rt-utils")});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  for (const auto& p : imported->problems) ADD_FAILURE() << p.status.to_string();
  ASSERT_EQ(imported->images.size(), 1u);
  const double voxel_mm2 = 0.488281 * 0.488281;
  ASSERT_EQ(imported->structure_sets.size(), 3u);
  for (const auto& set : imported->structure_sets) {
    EXPECT_EQ(set.referenced_series_uid, imported->images[0].series_uid) << set.path;
    if (set.path.ends_with("/rt.dcm")) {
      // Outer ccw contour with an inner cw hole on z = 60: 351.5 mm2 of ring.
      ASSERT_EQ(set.converted.structures.size(), 1u);
      const double count = static_cast<double>(voxel_count(set.converted.structures[0].volume));
      EXPECT_NEAR(count * voxel_mm2, 351.5, 0.1 * 351.5) << "the hole must be subtracted";
    } else {
      // MIM's contours on z = 60, 65, 70; the CT here has only the first two slices.
      ASSERT_EQ(set.converted.structures.size(), 4u) << set.path;
      for (const auto& s : set.converted.structures) EXPECT_EQ(s.contours_outside_grid, 1) << s.name;
    }
  }
}

}  // namespace
}  // namespace soiq::dicom
