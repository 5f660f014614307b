// The case table read off VTK in one run over all 256 patterns equals VTK's answer for each
// pattern run alone, triangle for triangle and winding included.
#include "core/io/marching_cubes_cases.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace soiq {
namespace {

TEST(MarchingCubesCases, OneRunOverAllPatternsEqualsEachPatternAlone) {
  const CubeCaseTable& table = marching_cubes_cases();
  CubeCaseTable oracle = marching_cubes_cases_one_by_one();
  size_t triangles = 0;
  for (size_t p = 0; p < 256; ++p) {
    std::vector<CubeCaseTriangle> got = table.triangles[p], want = oracle.triangles[p];
    // The same triangles; their order within a case may follow the image's traversal.
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want) << "pattern " << p;
    triangles += want.size();
  }
  EXPECT_TRUE(oracle.triangles[0].empty());
  EXPECT_TRUE(oracle.triangles[255].empty());
  EXPECT_EQ(oracle.triangles[1].size(), 1u);  // one corner inside: one triangle
  EXPECT_GT(triangles, 256u);
}

}  // namespace
}  // namespace soiq
