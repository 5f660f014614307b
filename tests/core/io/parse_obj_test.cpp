// soiq's own OBJ parser: VTK's writer and reader are the oracle on well-formed files; hostile
// inputs each give one INVALID_ARGUMENT line naming the file, the line and the token.
#include "core/io/parse_obj.h"

#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/geometry/mesh_defects.h"
#include "core/geometry/primitives.h"
#include "core/io/write_mesh.h"
#include "tests/core/io/io_test_files.h"
#include "tests/core/io/mesh_test_shapes.h"
#include "tests/core/io/vtk_mesh_oracle.h"

namespace soiq {
namespace {

using testing_io::expect_invalid;
using testing_io::file_bytes;

using Triangles = std::vector<std::array<int32_t, 3>>;

const char* kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(ParseObj, FromVtkWriterEqualsVtkReaderVertexForVertex) {
  for (const TriangleMesh& shape : {testing_io::awkward_box(), torus({0, 0, 0}, 10, 3, 16, 8)}) {
    const std::string path = testing_io::scratch_path("oracle.obj");
    ASSERT_TRUE(write_mesh(shape, path).ok());
    const auto ours = parse_obj(file_bytes(path), "oracle.obj");
    ASSERT_TRUE(ours.ok()) << ours.status().to_string();
    const TriangleMesh vtk = testing_io::read_with_vtk(path);
    // vtkOBJReader keeps float32; ours keeps the written decimal as a double.
    EXPECT_EQ(testing_io::rounded_to_float(*ours).vertices_mm, vtk.vertices_mm);
    EXPECT_EQ(ours->triangles, vtk.triangles);
    EXPECT_TRUE(mesh_defects(*ours).closed());
  }
}

TEST(ParseObj, PolygonsAreFannedFromTheirFirstCorner) {
  const auto mesh = parse_obj(std::string(kSquare) + "v 0.5 2 0\nf 1 2 3 5 4\n", "fan.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles, (Triangles{{0, 1, 2}, {0, 2, 4}, {0, 4, 3}}));
}

TEST(ParseObj, RelativeIndicesCountBackFromTheLastVertexSoFar) {
  const auto mesh = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf -4 -1 -3\n", "rel.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles, (Triangles{{0, 1, 2}, {0, 3, 1}}));
}

TEST(ParseObj, TextureAndNormalFormsGiveTheVertexIndex) {
  const auto mesh = parse_obj(std::string(kSquare) + "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n" +
                                  "f 1/1 2/2 3/3\nf 1//1 3//1 4//1\nf 1/1/1 3/-1/-1 4/3/1\n",
                              "forms.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles, (Triangles{{0, 1, 2}, {0, 2, 3}, {0, 2, 3}}));
}

TEST(ParseObj, RecordsWithoutGeometryAndCommentsAreIgnoredAndMtllibIsNeverOpened) {
  const auto mesh = parse_obj(
      "# made by hand\nmtllib /nonexistent/secret.mtl\no thing\ng group\ns 1\n"
      "usemtl skin\n" +
          std::string(kSquare) + "f 1 2 3 # a comment\nl 1 3\np 2\ncstype bezier\nf 1 3 4\n",
      "extra.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 2u);
}

TEST(ParseObj, VertexColoursAndWAreAllowedAndSkipped) {
  const auto mesh = parse_obj("v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0\nf 1 2 3\n", "colours.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->vertices_mm[1], (Vec3{1, 0, 0}));
}

TEST(ParseObj, FaceBeforeItsVerticesIsAccepted) {
  const auto mesh = parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "forward.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 1u);
}

class ParseObjBadCoordinate : public ::testing::TestWithParam<std::string> {};

TEST_P(ParseObjBadCoordinate, IsInvalidArgumentNamingLineAndToken) {
  // vtkOBJReader read "nan" as 0 and "5abc" as 5.
  const auto mesh = parse_obj("v 0 0 0\nv 1 0 0\nv 0 " + GetParam() + " 0\nf 1 2 3\n", "bad.obj");
  expect_invalid(mesh, "OBJ 'bad.obj' line 3: '" + GetParam() + "'");
}

INSTANTIATE_TEST_SUITE_P(Tokens, ParseObjBadCoordinate,
                         ::testing::Values("nan", "NaN", "inf", "-infinity", "5abc", "1e999", "1..2", "+"),
                         [](const auto& info) { return "case" + std::to_string(info.index); });

TEST(ParseObj, ShortVertexIsInvalidArgument) {
  expect_invalid(parse_obj("v 0 0\n", "short.obj"), "OBJ 'short.obj' line 1: vertex has 2 values; 3 are needed");
}

TEST(ParseObj, BadTextureValueIsInvalidArgument) {
  expect_invalid(parse_obj("vt 0 nan\n", "vt.obj"), "line 1: 'nan' is not a finite number");
}

TEST(ParseObj, ZeroIndexIsInvalidArgument) {
  expect_invalid(parse_obj(std::string(kSquare) + "f 0 1 2\n", "zero.obj"),
                 "OBJ 'zero.obj' line 5: malformed face index '0' (OBJ indices start at 1)");
}

TEST(ParseObj, IndexBeyondTheVerticesIsInvalidArgumentNamingItsLine) {
  expect_invalid(parse_obj(std::string(kSquare) + "f 1 2 3\nf 1 2 7\nf 1 2 3\n", "oob.obj"),
                 "OBJ 'oob.obj' line 6: face index 7 is out of range (the file has 4 vertices)");
}

TEST(ParseObj, RelativeIndexBeforeTheFirstVertexIsInvalidArgument) {
  expect_invalid(parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 -3\n", "neg.obj"),
                 "face index -3 is out of range (2 vertices defined so far)");
}

TEST(ParseObj, NormalIndexOutOfRangeIsInvalidArgument) {
  expect_invalid(parse_obj(std::string(kSquare) + "vn 0 0 1\nf 1//1 2//2 3//1\n", "vn.obj"),
                 "face index 2 is out of range (the file has 1 normals)");
}

TEST(ParseObj, MalformedCornersAreInvalidArgument) {
  for (const char* corner : {"1a", "1/2/3/4", "x", "1.5", "99999999999"}) {
    const auto mesh =
        parse_obj(std::string(kSquare) + "vt 0 0\nvt 0 0\nvt 0 0\nvn 0 0 1\nf 1 2 " + corner + "\n", "corner.obj");
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << corner;
    EXPECT_NE(mesh.status().message().find("line 9"), std::string::npos) << mesh.status().message();
  }
}

TEST(ParseObj, FaceWithTwoCornersIsInvalidArgument) {
  expect_invalid(parse_obj(std::string(kSquare) + "f 1 2\n", "two.obj"), "face has 2 corners; a face needs at least 3");
}

TEST(ParseObj, FreeFormGeometryIsRefusedNotDropped) {
  expect_invalid(parse_obj(std::string(kSquare) + "surf 0 1 0 1 1 2 3 4\n", "surf.obj"), "free-form geometry");
}

TEST(ParseObj, HugeOrBinaryTokensAreQuotedShortAndPrintable) {
  // A hostile token must not make a huge or multi-line message (soiqd logs messages as logfmt).
  const auto mesh = parse_obj("v 0 0 " + std::string(100000, '7') + "x\n", "long.obj");
  expect_invalid(mesh, "line 1: '7777777777777777777777777777777777777777...' is not a number");
  expect_invalid(parse_obj(std::string("v 0 0 1\x01\x7f\n"), "ctrl.obj"), "'1?\?' is not a number");
}

TEST(ParseObj, FileWithoutFacesHasNoTriangles) {
  const auto mesh = parse_obj("v 0 0 0\n", "points.obj");
  ASSERT_TRUE(mesh.ok());
  EXPECT_TRUE(mesh->triangles.empty());
}

}  // namespace
}  // namespace soiq
