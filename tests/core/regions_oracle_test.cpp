// Regions around and within a structure: shell(r) and core(r) against a brute-force oracle voxel for
// voxel, the cases decided by construction, and the choice of method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/regions/ball_morphology.h"
#include "core/regions/regions.h"
#include "tests/core/regions_blob.h"

namespace soiq {
namespace {

using testing::random_blob;

// The region by definition: every pair of voxels of the grid.
Mask brute_force_region(const Mask& m, RegionKind kind, double r) {
  const auto& d = m.geometry.dims;
  const auto& s = m.geometry.spacing_mm;
  Mask out{m.geometry, std::vector<uint8_t>(m.voxels.size(), 0)};
  for (int64_t k = 0; k < d[2]; ++k)
    for (int64_t j = 0; j < d[1]; ++j)
      for (int64_t i = 0; i < d[0]; ++i) {
        const bool in = m.voxels[size_t(i + d[0] * (j + d[1] * k))] != 0;
        if (in == (kind == RegionKind::kShell)) continue;  // shell: outside voxels; core: inside ones
        bool near = false;                                 // a voxel of the other kind within r
        // Only voxels within ceil(r / spacing) steps on each axis can be within r mm (one more step
        // is searched, so the oracle does not share that argument with the code under test).
        const int64_t wi = int64_t(std::ceil(r / s[0])) + 1, wj = int64_t(std::ceil(r / s[1])) + 1,
                      wk = int64_t(std::ceil(r / s[2])) + 1;
        for (int64_t c = std::max<int64_t>(0, k - wk); c <= std::min(d[2] - 1, k + wk) && !near; ++c)
          for (int64_t b = std::max<int64_t>(0, j - wj); b <= std::min(d[1] - 1, j + wj) && !near; ++b)
            for (int64_t a = std::max<int64_t>(0, i - wi); a <= std::min(d[0] - 1, i + wi) && !near; ++a) {
              if ((m.voxels[size_t(a + d[0] * (b + d[1] * c))] != 0) == in) continue;
              const double x = double(i - a) * s[0], y = double(j - b) * s[1], z = double(k - c) * s[2];
              near = x * x + y * y + z * z <= r * r * (1 + 1e-12);  // the contract's tie rule
            }
        const bool selected = kind == RegionKind::kShell ? near : !near;
        out.voxels[size_t(i + d[0] * (j + d[1] * k))] = selected ? 1 : 0;
      }
  return out;
}

struct OracleCase {
  RegionKind kind;
  double radius_mm;
  bool empty;  // the region is empty by construction
};

class RegionsOracle : public ::testing::TestWithParam<OracleCase> {};

TEST_P(RegionsOracle, EqualsBruteForceVoxelForVoxelOnAnAnisotropicGrid) {
  const OracleCase c = GetParam();
  for (uint64_t seed : {1, 2, 3}) {
    const Mask blob = random_blob(seed);
    const Mask brute = brute_force_region(blob, c.kind, c.radius_mm);
    const RunLengthVolume want = from_mask(brute);
    if (!c.empty) {
      ASSERT_GT(voxel_count(want), 0);
    }
    // Each way to a region: on the runs, by the distance transform, and the cheaper of the two.
    for (const RegionMethod method : {RegionMethod::kCheapest, RegionMethod::kRuns, RegionMethod::kTransform}) {
      auto got = region(from_mask(blob), {c.kind, c.radius_mm}, {.threads = 2, .method = method});
      ASSERT_TRUE(got.ok()) << got.status().to_string();
      auto cmp = compare(*got, want);
      ASSERT_TRUE(cmp.ok());
      EXPECT_EQ(cmp->only_a + cmp->only_b, 0) << "seed " << seed << ", method " << int(method);
    }
    if (c.kind == RegionKind::kShell) {  // the dilation itself: the structure plus its shell
      Mask dilated = brute;
      for (size_t n = 0; n < blob.voxels.size(); ++n) dilated.voxels[n] |= blob.voxels[n];
      auto cmp = compare(ball_dilation(from_mask(blob), c.radius_mm), from_mask(dilated));
      ASSERT_TRUE(cmp.ok());
      EXPECT_EQ(cmp->only_a + cmp->only_b, 0) << "seed " << seed;
    }
    if (c.kind == RegionKind::kCore) {  // the erosion itself, whichever way region() chose
      auto cmp = compare(ball_erosion(from_mask(blob), c.radius_mm), want);
      ASSERT_TRUE(cmp.ok());
      EXPECT_EQ(cmp->only_a + cmp->only_b, 0) << "seed " << seed;
    }
  }
}

// Radii include ties with the grid (2.1 = 3 x 0.7, 2.5 = one z step) and one under every spacing,
// whose shell is empty: no two centres are closer than 0.7 mm.
std::vector<OracleCase> oracle_cases() {
  std::vector<OracleCase> cases{{RegionKind::kShell, 0.5, true}};
  for (double r : {1.25, 2.1, 2.5, 4.2}) cases.push_back({RegionKind::kShell, r, false});
  for (double r : {0.7, 1.25, 2.1, 2.5}) cases.push_back({RegionKind::kCore, r, false});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Radii, RegionsOracle, ::testing::ValuesIn(oracle_cases()));

// A radius far beyond the grid (an absurd request) answers at once with what the whole grid holds:
// it used to loop over a billion offset lines (1e9 mm), or overflow to an empty shell (1e300 mm).
TEST(Regions, RadiusFarBeyondTheGridSelectsWhatTheGridHolds) {
  const Mask blob = random_blob(5);
  Mask outside = blob, full = blob;
  for (size_t n = 0; n < blob.voxels.size(); ++n) outside.voxels[n] = uint8_t(1 - blob.voxels[n]), full.voxels[n] = 1;
  for (const double r : {1e9, 1e300}) {
    for (const RegionMethod method : {RegionMethod::kCheapest, RegionMethod::kRuns, RegionMethod::kTransform}) {
      const RegionOptions options{.threads = 1, .method = method};
      auto shell = region(from_mask(blob), {RegionKind::kShell, r}, options);
      ASSERT_TRUE(shell.ok()) << shell.status().to_string();
      auto cmp = compare(*shell, from_mask(outside));
      ASSERT_TRUE(cmp.ok());
      EXPECT_EQ(cmp->only_a + cmp->only_b, 0) << r << " " << int(method);
      auto core = region(from_mask(blob), {RegionKind::kCore, r}, options);
      ASSERT_TRUE(core.ok());
      EXPECT_EQ(voxel_count(*core), 0) << r << " " << int(method);
      // With no outside voxel in the grid, nothing erodes a structure that fills it.
      auto whole = region(from_mask(full), {RegionKind::kCore, r}, options);
      ASSERT_TRUE(whole.ok());
      EXPECT_EQ(voxel_count(*whole), int64_t(full.voxels.size())) << r << " " << int(method);
    }
  }
}

TEST(Regions, InsideIsTheStructureItself) {
  const RunLengthVolume v = from_mask(random_blob(4));
  auto got = region(v, {RegionKind::kInside, 0});
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->runs, v.runs);
  EXPECT_EQ(got->line_start, v.line_start);
}

TEST(Regions, ShellIsClippedToTheGrid) {
  // One voxel in a corner: shell(1) has the 3 face neighbours inside the grid, not 6.
  Mask m;
  m.geometry.dims = {4, 4, 4};
  m.voxels.assign(64, 0);
  m.voxels[0] = 1;
  auto got = region(from_mask(m), {RegionKind::kShell, 1.0});
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(voxel_count(*got), 3);
}

TEST(Regions, ShellOfAnEmptyStructureIsEmpty) {
  ImageGeometry g;
  g.dims = {5, 5, 5};
  auto got = region(empty_volume(g), {RegionKind::kShell, 3.0});
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(voxel_count(*got), 0);
}

// The cost model's choice: a thin ball on a long line goes to the runs, a ball whose cross section
// dwarfs the box's width to the transform (each is measured side by side in BENCHMARKS.md).
TEST(Regions, CheapestMethodFollowsTheBallCrossSection) {
  const RunLengthVolume blob = from_mask(random_blob(8));
  auto thin = cheapest_region_method(blob, {RegionKind::kCore, 0.7});
  ASSERT_TRUE(thin.ok());
  EXPECT_EQ(*thin, RegionMethod::kRuns);
  auto wide = cheapest_region_method(blob, {RegionKind::kShell, 40});
  ASSERT_TRUE(wide.ok());
  EXPECT_EQ(*wide, RegionMethod::kTransform);
  EXPECT_FALSE(cheapest_region_method(blob, {RegionKind::kShell, -1}).ok());
}

}  // namespace
}  // namespace soiq
