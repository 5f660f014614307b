// Lossless round trip, on every real mask we ship: mask -> marching cubes (iso 0.5) -> 1D method on
// the mask's own grid gives the mask back, voxel for voxel (the paper reports 97.1-99.8 % IoU and
// calls its conversion "not lossless"; ours is).
#include <gtest/gtest.h>

#include <string>

#include "core/io/marching_cubes.h"
#include "core/io/read_image.h"
#include "core/voxelize/voxelize_1d.h"
#include "tests/support/simulated_models.h"

namespace soiq {
namespace {

struct RealMask {
  std::string file;         // under tests/data
  int label;                // -1: nonzero
  int64_t expected_voxels;  // stated in the data set's README, or -1
};

class RoundTrip : public ::testing::TestWithParam<RealMask> {};

TEST_P(RoundTrip, MarchingCubesSurfaceConvertsBackToTheSameMask) {
  const RealMask& c = GetParam();
  auto image = read_image(std::string(SOIQ_TEST_DATA_DIR) + "/" + c.file);
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  const Mask mask = mask_from_image(*image, c.label);
  const RunLengthVolume original = from_mask(mask);
  if (c.expected_voxels >= 0) {
    EXPECT_EQ(voxel_count(original), c.expected_voxels);
  }
  ASSERT_GT(voxel_count(original), 0);

  auto surface = marching_cubes(mask);
  ASSERT_TRUE(surface.ok()) << surface.status().to_string();
  auto back = voxelize_1d(*surface, mask.geometry);
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  EXPECT_TRUE(back->defects.closed());
  auto cmp = compare(original, back->volume);
  ASSERT_TRUE(cmp.ok());
  EXPECT_EQ(cmp->only_a, 0) << c.file << ": voxels lost";
  EXPECT_EQ(cmp->only_b, 0) << c.file << ": voxels added";
}

std::vector<RealMask> real_masks() {
  std::vector<RealMask> ms = {
      {"pyradiomics/brain1_label.nrrd", 1, 4137},  // direction diag(1,-1,1), two pieces, genus 2
      {"ibsi_digital_phantom/mask.nii.gz", -1, -1},
  };
  for (const char* patient : {"STS_002", "STS_008", "STS_012", "STS_025"}) {
    for (const char* modality : {"CT", "MR_T1", "PET"}) {
      ms.push_back({std::string("sts/") + patient + "/" + modality + "_mask.nii.gz", -1, -1});
    }
  }
  return ms;
}

INSTANTIATE_TEST_SUITE_P(RealMasks, RoundTrip, ::testing::ValuesIn(real_masks()), [](const auto& info) {
  std::string n = info.param.file;
  for (char& ch : n) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return n;
});

// The paper's simulated models SM1-SM11 at 1 mm (tests/support/simulated_models.h): V1 is the analytic
// voxel-centre volume, S1 its marching-cubes surface; S1 converted back must be V1 exactly.
class SimulatedRoundTrip : public ::testing::TestWithParam<bench::SimModel> {};

TEST_P(SimulatedRoundTrip, SurfaceConvertsBackToTheAnalyticVolume) {
  const Mask v1 = bench::simulated_volume(GetParam(), 1.0);
  auto s1 = marching_cubes(v1);
  ASSERT_TRUE(s1.ok()) << s1.status().to_string();
  VoxelizeOptions options;
  options.threads = 2;
  auto v2 = voxelize_1d(*s1, v1.geometry, options);
  ASSERT_TRUE(v2.ok()) << v2.status().to_string();
  auto cmp = compare(from_mask(v1), v2->volume);
  ASSERT_TRUE(cmp.ok());
  EXPECT_GT(cmp->count_a, 100000);
  EXPECT_EQ(cmp->only_a + cmp->only_b, 0) << GetParam().name;
}

INSTANTIATE_TEST_SUITE_P(SM1toSM11, SimulatedRoundTrip, ::testing::ValuesIn(bench::simulated_models()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace soiq
