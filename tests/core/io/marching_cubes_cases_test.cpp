// The case table read off VTK in one run over all 256 patterns equals VTK's answer for each
// pattern run alone, triangle for triangle and winding included; and the table committed as data
// (core/features/marching_cubes_table.cpp, which the features use) is the installed VTK's.
#include "core/io/marching_cubes_cases.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/features/marching_cubes_table.h"

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

TEST(MarchingCubesCases, TheCommittedTableIsTheInstalledVtksTriangleForTriangle) {
  const CubeCaseTable& vtk = marching_cubes_cases();
  const CubeCaseTable& committed = marching_cubes_table();
  for (size_t p = 0; p < 256; ++p) {
    EXPECT_EQ(committed.triangles[p], vtk.triangles[p])
        << "pattern " << p
        << ": regenerate core/features/marching_cubes_table.cpp (tools/make_marching_cubes_table.cpp)";
  }
}

}  // namespace
}  // namespace soiq
