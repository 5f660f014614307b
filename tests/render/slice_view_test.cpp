// How a plane of a grid is shown (render/slice_view.h): the letters at the screen's edges from the
// direction cosines, and slices checked against a brute-force oracle that knows nothing of axes
// or flips: a voxel's column on the screen is the rank of its centre's position along the screen's
// right (in LPS mm), its row the rank along the screen's down.
#include "render/slice_view.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <tuple>

namespace soiq::render {
namespace {

// Columns of the direction matrix: the LPS directions of i, j and k.
ImageGeometry grid(const Vec3& i, const Vec3& j, const Vec3& k, std::array<int64_t, 3> dims = {5, 4, 3}) {
  ImageGeometry g;
  g.origin_mm = {-12.5, 30, 7};
  g.spacing_mm = {0.7, 0.9, 2.5};
  g.dims = dims;
  for (int row = 0; row < 3; ++row) g.direction[row] = {i[row], j[row], k[row]};
  return g;
}

ImageGeometry identity_grid() { return grid({1, 0, 0}, {0, 1, 0}, {0, 0, 1}); }
ImageGeometry flipped_grid() { return grid({-1, 0, 0}, {0, -1, 0}, {0, 0, -1}); }
// A sagittal series: i runs anterior to posterior, j superior to inferior, k right to left.
ImageGeometry sagittal_grid() { return grid({0, 1, 0}, {0, 0, -1}, {1, 0, 0}); }
// A coronal series: i right to left, j superior to inferior, k anterior to posterior.
ImageGeometry coronal_grid() { return grid({1, 0, 0}, {0, 0, -1}, {0, 1, 0}); }

Mat3 rotation_z(double degrees) {
  const double a = degrees * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  return {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}
Mat3 rotation_x(double degrees) {
  const double a = degrees * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  return {{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
}
Mat3 times(const Mat3& a, const Mat3& b) {
  Mat3 m{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m[r][c] = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
  }
  return m;
}

struct Letters {
  std::string left, right, top, bottom;
};

Letters letters_of(const ImageGeometry& g, Plane plane) {
  const Result<SliceAxes> axes = slice_axes(g, plane);
  EXPECT_TRUE(axes.ok()) << axes.status().to_string();
  if (!axes.ok()) return {};
  return {axes->left, axes->right, axes->top, axes->bottom};
}

void expect_letters(const Letters& have, const Letters& want, const std::string& what) {
  EXPECT_EQ(have.left, want.left) << what;
  EXPECT_EQ(have.right, want.right) << what;
  EXPECT_EQ(have.top, want.top) << what;
  EXPECT_EQ(have.bottom, want.bottom) << what;
}

TEST(SliceAxes, AxisAlignedGridsShowAsRadiologyViewersDoWhateverTheirStorageOrder) {
  // Right on the screen's left; anterior (axial) or superior (coronal, sagittal) up; sagittal with
  // anterior on the left. The same for every grid: that is what the matching and the flips are for.
  const std::vector<std::pair<std::string, ImageGeometry>> grids = {{"identity", identity_grid()},
                                                                    {"flipped", flipped_grid()},
                                                                    {"sagittal-acquired", sagittal_grid()},
                                                                    {"coronal-acquired", coronal_grid()}};
  for (const auto& [name, g] : grids) {
    expect_letters(letters_of(g, Plane::kAxial), {"R", "L", "A", "P"}, name + " axial");
    expect_letters(letters_of(g, Plane::kCoronal), {"R", "L", "S", "I"}, name + " coronal");
    expect_letters(letters_of(g, Plane::kSagittal), {"A", "P", "S", "I"}, name + " sagittal");
  }
}

TEST(SliceAxes, MatchesVoxelAxesAndFlipsFromTheCosines) {
  const SliceAxes identity_axial = *slice_axes(identity_grid(), Plane::kAxial);
  EXPECT_EQ(std::tie(identity_axial.across_axis, identity_axial.down_axis, identity_axial.normal_axis),
            std::make_tuple(0, 1, 2));
  EXPECT_FALSE(identity_axial.flip_across);
  EXPECT_FALSE(identity_axial.flip_down);
  EXPECT_EQ(identity_axial.width, 5);
  EXPECT_EQ(identity_axial.height, 4);
  EXPECT_EQ(identity_axial.slice_count, 3);
  EXPECT_DOUBLE_EQ(identity_axial.pixel_width_mm, 0.7);
  EXPECT_DOUBLE_EQ(identity_axial.pixel_height_mm, 0.9);

  // Coronal of an axial series: superior up, so k (pointing superior) runs bottom to top.
  const SliceAxes identity_coronal = *slice_axes(identity_grid(), Plane::kCoronal);
  EXPECT_EQ(std::tie(identity_coronal.across_axis, identity_coronal.down_axis, identity_coronal.normal_axis),
            std::make_tuple(0, 2, 1));
  EXPECT_FALSE(identity_coronal.flip_across);
  EXPECT_TRUE(identity_coronal.flip_down);
  EXPECT_DOUBLE_EQ(identity_coronal.pixel_height_mm, 2.5);

  const SliceAxes flipped_axial = *slice_axes(flipped_grid(), Plane::kAxial);
  EXPECT_TRUE(flipped_axial.flip_across);
  EXPECT_TRUE(flipped_axial.flip_down);

  // Axial of a sagittal series: across is k (right to left), down is i (anterior to posterior).
  const SliceAxes sagittal_axial = *slice_axes(sagittal_grid(), Plane::kAxial);
  EXPECT_EQ(std::tie(sagittal_axial.across_axis, sagittal_axial.down_axis, sagittal_axial.normal_axis),
            std::make_tuple(2, 0, 1));
  EXPECT_FALSE(sagittal_axial.flip_across);
  EXPECT_FALSE(sagittal_axial.flip_down);
  EXPECT_EQ(sagittal_axial.slice_count, 4);
  const SliceAxes sagittal_sagittal = *slice_axes(sagittal_grid(), Plane::kSagittal);
  EXPECT_EQ(sagittal_sagittal.normal_axis, 2);
  EXPECT_FALSE(sagittal_sagittal.flip_down);  // j already runs superior to inferior
}

TEST(SliceAxes, AnObliqueGridNamesTheTwoOrThreeLargestComponentsInOrder) {
  // Turned 30 degrees about the feet-head axis: i = (0.87, 0.5, 0), j = (-0.5, 0.87, 0).
  ImageGeometry turned = identity_grid();
  turned.direction = rotation_z(30);
  expect_letters(letters_of(turned, Plane::kAxial), {"RA", "LP", "AL", "PR"}, "turned axial");
  expect_letters(letters_of(turned, Plane::kCoronal), {"RA", "LP", "S", "I"}, "turned coronal");
  // Then 20 degrees about left-right: i = (0.87, 0.47, 0.17), every component counts.
  ImageGeometry tilted = identity_grid();
  tilted.direction = times(rotation_x(20), rotation_z(30));
  const Letters axial = letters_of(tilted, Plane::kAxial);
  EXPECT_EQ(axial.right, "LPS");
  EXPECT_EQ(axial.left, "RAI");
  EXPECT_EQ(axial.bottom.size(), 3u) << axial.bottom;
}

TEST(SliceAxes, MatchesOneToOneWhereTwoAxesLeanToTheSamePatientAxis) {
  // Both i and j have their largest component along x; the matching still gives each its own.
  const double h = std::sqrt(0.5);
  const ImageGeometry g = grid({h, 0.5, 0.5}, {h, -0.5, -0.5}, {0, h, -h});
  for (Plane plane : {Plane::kAxial, Plane::kCoronal, Plane::kSagittal}) {
    const Result<SliceAxes> axes = slice_axes(g, plane);
    ASSERT_TRUE(axes.ok()) << axes.status().to_string();
    EXPECT_NE(axes->across_axis, axes->down_axis);
    EXPECT_EQ(axes->across_axis + axes->down_axis + axes->normal_axis, 3);
  }
}

TEST(SliceAxes, RefusesAnInvalidGridAndUnknownPlanes) {
  ImageGeometry bad = identity_grid();
  bad.direction = {{{1, 0, 0}, {1, 0, 0}, {0, 0, 1}}};
  const Result<SliceAxes> axes = slice_axes(bad, Plane::kAxial);
  ASSERT_FALSE(axes.ok());
  EXPECT_EQ(axes.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(axes.status().message().find("axial"), std::string::npos) << axes.status().message();

  EXPECT_EQ(*plane_of_name("coronal"), Plane::kCoronal);
  const Result<Plane> plane = plane_of_name("oblique");
  ASSERT_FALSE(plane.ok());
  EXPECT_EQ(plane.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(plane.status().message().find("'oblique'"), std::string::npos);
  EXPECT_NE(plane.status().message().find("sagittal"), std::string::npos);
}

// The oracle: screen (column, row) of every voxel on slice k, by ranks of LPS positions.
struct Oracle {
  int64_t width = 0, height = 0;
  std::map<std::array<int64_t, 3>, std::pair<int64_t, int64_t>> pixel;  // voxel -> (x, y)
};

Oracle oracle(const ImageGeometry& g, Plane plane, int normal_axis, int64_t k) {
  const Vec3 right = plane == Plane::kSagittal ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
  const Vec3 down = plane == Plane::kAxial ? Vec3{0, 1, 0} : Vec3{0, 0, -1};
  std::vector<std::array<int64_t, 3>> voxels;
  std::vector<double> across, along;
  for (int64_t c = 0; c < g.dims[2]; ++c) {
    for (int64_t b = 0; b < g.dims[1]; ++b) {
      for (int64_t a = 0; a < g.dims[0]; ++a) {
        const std::array<int64_t, 3> ijk{a, b, c};
        if (ijk[normal_axis] != k) continue;
        const Vec3 p = g.index_to_physical({double(a), double(b), double(c)});
        voxels.push_back(ijk);
        across.push_back(dot(p, right));
        along.push_back(dot(p, down));
      }
    }
  }
  const auto rank = [](const std::vector<double>& values, double v) {
    std::vector<double> distinct = values;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end(), [](double x, double y) { return y - x < 1e-6; }),
                   distinct.end());
    return std::pair<int64_t, int64_t>(std::lower_bound(distinct.begin(), distinct.end(), v - 1e-6) - distinct.begin(),
                                       static_cast<int64_t>(distinct.size()));
  };
  Oracle out;
  for (size_t n = 0; n < voxels.size(); ++n) {
    const auto [x, width] = rank(across, across[n]);
    const auto [y, height] = rank(along, along[n]);
    out.pixel[voxels[n]] = {x, y};
    out.width = width;
    out.height = height;
  }
  return out;
}

int64_t index_of(const ImageGeometry& g, const std::array<int64_t, 3>& ijk) {
  return ijk[0] + g.dims[0] * (ijk[1] + g.dims[1] * ijk[2]);
}

class SlicesAgainstOracle : public ::testing::TestWithParam<std::tuple<int, Plane>> {
 protected:
  static ImageGeometry geometry(int which) {
    switch (which) {
      case 0:
        return identity_grid();
      case 1:
        return flipped_grid();
      case 2:
        return sagittal_grid();
      default:
        return coronal_grid();
    }
  }
};

TEST_P(SlicesAgainstOracle, EveryPixelOfEverySliceIsTheVoxelTheOracleNames) {
  const auto [which, plane] = GetParam();
  const ImageGeometry g = geometry(which);
  Image image{g, {}};
  Mask dense{g, {}};
  std::mt19937 random(42 + which);
  for (int64_t n = 0; n < g.voxel_count(); ++n) {
    image.voxels.push_back(static_cast<float>(n));  // each voxel its own value
    dense.voxels.push_back(static_cast<uint8_t>(random() % 3 == 0));
  }
  const RunLengthVolume volume = from_mask(dense);
  const SliceAxes axes = *slice_axes(g, plane);
  const std::vector<int64_t> per_slice = inside_per_slice(volume, axes);
  ASSERT_EQ(static_cast<int64_t>(per_slice.size()), axes.slice_count);
  for (int64_t k = 0; k < axes.slice_count; ++k) {
    const Oracle o = oracle(g, plane, axes.normal_axis, k);
    const Result<SliceImage> slice = image_slice(image, axes, k);
    const Result<SliceMask> mask = mask_slice(volume, axes, k);
    ASSERT_TRUE(slice.ok()) << slice.status().to_string();
    ASSERT_TRUE(mask.ok()) << mask.status().to_string();
    ASSERT_EQ(slice->width, o.width);
    ASSERT_EQ(slice->height, o.height);
    ASSERT_EQ(mask->width, o.width);
    ASSERT_EQ(mask->height, o.height);
    int64_t inside = 0;
    for (const auto& [ijk, xy] : o.pixel) {
      const size_t pixel = static_cast<size_t>(xy.second * o.width + xy.first);
      const auto index = static_cast<size_t>(index_of(g, ijk));
      EXPECT_EQ(slice->values[pixel], image.voxels[index])
          << "k " << k << " voxel " << ijk[0] << "," << ijk[1] << "," << ijk[2];
      EXPECT_EQ(mask->inside[pixel], dense.voxels[index]) << "k " << k;
      inside += dense.voxels[index];
    }
    EXPECT_EQ(per_slice[static_cast<size_t>(k)], inside) << "k " << k;  // the dense count
  }
}

INSTANTIATE_TEST_SUITE_P(GridsAndPlanes, SlicesAgainstOracle,
                         ::testing::Combine(::testing::Values(0, 1, 2, 3),
                                            ::testing::Values(Plane::kAxial, Plane::kCoronal, Plane::kSagittal)));

TEST(InsidePerSlice, CountsRunsThatCrossManySlices) {
  // A slab of whole rows across a grid shown sagittally: each run spans many slices (i fixed).
  ImageGeometry g = identity_grid();
  g.dims = {40, 6, 5};
  Mask dense{g, std::vector<uint8_t>(static_cast<size_t>(g.voxel_count()), 0)};
  for (int64_t k = 0; k < 5; ++k) {
    for (int64_t i = 3; i < 37; ++i) dense.voxels[static_cast<size_t>(i + 40 * (2 + 6 * k))] = 1;
  }
  const std::vector<int64_t> counts = inside_per_slice(from_mask(dense), *slice_axes(g, Plane::kSagittal));
  ASSERT_EQ(counts.size(), 40u);
  for (int64_t i = 0; i < 40; ++i) EXPECT_EQ(counts[static_cast<size_t>(i)], i >= 3 && i < 37 ? 5 : 0) << i;
}

TEST(ImageSlice, RefusesASliceOutOfRangeAndDataOfAnotherGrid) {
  const ImageGeometry g = identity_grid();
  const SliceAxes axes = *slice_axes(g, Plane::kAxial);
  const Image image{g, std::vector<float>(static_cast<size_t>(g.voxel_count()), 0)};
  for (int64_t k : {int64_t{-1}, int64_t{3}}) {
    const Result<SliceImage> slice = image_slice(image, axes, k);
    ASSERT_FALSE(slice.ok());
    EXPECT_EQ(slice.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(slice.status().message().find("out of range 0..2"), std::string::npos) << slice.status().message();
  }
  Image short_image = image;
  short_image.voxels.pop_back();
  EXPECT_EQ(image_slice(short_image, axes, 0).status().code(), StatusCode::kInvalidArgument);
  ImageGeometry other = g;
  other.dims = {4, 5, 3};
  const Result<SliceMask> mask = mask_slice(empty_volume(other), axes, 0);
  ASSERT_FALSE(mask.ok());
  EXPECT_EQ(mask.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mask.status().message().find("4x5x3"), std::string::npos) << mask.status().message();
}

}  // namespace
}  // namespace soiq::render
