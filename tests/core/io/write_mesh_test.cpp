#include "core/io/write_mesh.h"

#include <gtest/gtest.h>

#include <string>

#include "core/geometry/mesh_defects.h"
#include "core/io/read_mesh.h"
#include "tests/core/io/io_test_files.h"
#include "tests/core/io/mesh_test_shapes.h"

namespace soiq {
namespace {

using testing_io::awkward_box;
using testing_io::canonical_triangles;

class WriteMeshRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(WriteMeshRoundTrip, GivesBackTheSameTriangles) {
  const TriangleMesh box = awkward_box();
  const std::string path = testing_io::scratch_path("box" + GetParam());
  ASSERT_TRUE(write_mesh(box, path).ok());
  const auto back = read_mesh(path);
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  EXPECT_EQ(back->triangles.size(), box.triangles.size());
  EXPECT_TRUE(mesh_defects(*back).closed());
  TriangleMesh expected = box;
  if (GetParam() == ".stl" || GetParam() == ".ply") {
    // Both store float32 coordinates: exactly the double rounded to the nearest float.
    for (Vec3& v : expected.vertices_mm) v = {double(float(v[0])), double(float(v[1])), double(float(v[2]))};
  }
  if (GetParam() == ".obj") {
    // vtkOBJWriter prints coordinates with limited precision: compare to within its digits.
    ASSERT_EQ(back->vertices_mm.size(), box.vertices_mm.size());
    const auto got = canonical_triangles(*back);
    const auto want = canonical_triangles(expected);
    for (size_t t = 0; t < got.size(); ++t) {
      for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[t][c][a], want[t][c][a], 1e-5);
      }
    }
    return;
  }
  EXPECT_EQ(canonical_triangles(*back), canonical_triangles(expected));
}

INSTANTIATE_TEST_SUITE_P(Formats, WriteMeshRoundTrip, ::testing::Values(".stl", ".obj", ".ply", ".vtk", ".vtp"),
                         [](const auto& info) { return info.param.substr(1); });

TEST(WriteMesh, UnknownExtensionIsInvalidArgument) {
  const Status s = write_mesh(awkward_box(), testing_io::scratch_path("box.3ds"));
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("unknown mesh extension '.3ds'"), std::string::npos) << s.message();
}

TEST(WriteMesh, MissingDirectoryIsNotFound) {
  const Status s = write_mesh(awkward_box(), testing_io::scratch_path("nowhere/box.stl"));
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_NE(s.message().find("directory does not exist"), std::string::npos) << s.message();
}

TEST(WriteMesh, TriangleIndexOutOfRangeIsInvalidArgument) {
  TriangleMesh mesh = awkward_box();
  mesh.triangles.push_back({0, 1, 99});
  const Status s = write_mesh(mesh, testing_io::scratch_path("bad.vtp"));
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("out of range"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace soiq
