// soiq's own STL parser: VTK's writer and reader are the oracle on well-formed files; hostile
// inputs each give one INVALID_ARGUMENT line naming the file and the problem.
#include "core/io/parse_stl.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
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

// A binary STL of the given facets (normal zero), with `header` at the start of its 80 bytes.
std::string binary_stl(const std::vector<std::array<std::array<float, 3>, 3>>& facets, std::string header = "") {
  header.resize(80, ' ');
  std::string bytes = header;
  const uint32_t n = uint32_t(facets.size());
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : facets) {
    const float normal[3] = {0, 0, 0};
    bytes.append(reinterpret_cast<const char*>(normal), 12);
    for (const auto& v : t) bytes.append(reinterpret_cast<const char*>(v.data()), 12);
    bytes.append(2, '\0');
  }
  return bytes;
}

std::string ascii_facet(const std::string& a, const std::string& b, const std::string& c) {
  return "facet normal 0 0 1\nouter loop\nvertex " + a + "\nvertex " + b + "\nvertex " + c + "\nendloop\nendfacet\n";
}

TEST(ParseStl, BinaryFromVtkWriterEqualsVtkReaderVertexForVertex) {
  for (const TriangleMesh& shape : {testing_io::awkward_box(), uv_sphere({1, 2, 3}, 10, 12, 24)}) {
    const std::string path = testing_io::scratch_path("oracle_binary.stl");
    ASSERT_TRUE(write_mesh(shape, path).ok());
    const auto ours = parse_stl(file_bytes(path), "oracle_binary.stl");
    ASSERT_TRUE(ours.ok()) << ours.status().to_string();
    const TriangleMesh vtk = testing_io::read_with_vtk(path);
    EXPECT_EQ(ours->vertices_mm, vtk.vertices_mm);  // float32 widened exactly, first-seen order
    EXPECT_EQ(ours->triangles, vtk.triangles);
    EXPECT_TRUE(mesh_defects(*ours).closed());
  }
}

TEST(ParseStl, AsciiFromVtkWriterEqualsVtkReaderToFloatPrecision) {
  const TriangleMesh shape = uv_sphere({-5, 0, 7}, 3, 8, 16);
  const std::string path = testing_io::scratch_path("oracle_ascii.stl");
  ASSERT_TRUE(testing_io::write_ascii_stl_with_vtk(shape, path));
  const auto ours = parse_stl(file_bytes(path), "oracle_ascii.stl");
  ASSERT_TRUE(ours.ok()) << ours.status().to_string();
  const TriangleMesh vtk = testing_io::read_with_vtk(path);
  // vtkSTLReader keeps float32; ours keeps the written decimal as a double.
  EXPECT_EQ(testing_io::rounded_to_float(*ours).vertices_mm, vtk.vertices_mm);
  EXPECT_EQ(ours->triangles, vtk.triangles);
  EXPECT_TRUE(mesh_defects(*ours).closed());
}

TEST(ParseStl, CornersMergeInFirstSeenOrderAndMinusZeroEqualsZero) {
  const auto mesh = parse_stl(
      binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{1, 0, 0}, {1, 1, 0}, {-0.0f, 1, 0}}}}), "merge.stl");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->vertices_mm, (std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
  EXPECT_EQ(mesh->triangles, (std::vector<std::array<int32_t, 3>>{{0, 1, 2}, {1, 3, 2}}));
}

TEST(ParseStl, FacetWithCoincidentCornersIsDroppedAsVtkDid) {
  const auto mesh = parse_stl(binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}}}}),
                              "degenerate.stl");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 1u);
}

TEST(ParseStl, BinaryWhoseHeaderStartsWithSolidIsReadAsBinary) {
  const auto mesh =
      parse_stl(binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}}, "solid exported by a CAD tool"), "solid_header.stl");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 1u);
}

TEST(ParseStl, AsciiKeywordsInAnyCaseAndSeveralSolidsAreRead) {
  const std::string text =
      "SOLID a\r\n  FACET NORMAL 0 0 1\r\n OUTER LOOP\r\nVERTEX 0 0 0\r\nVERTEX 1 0 0\r\n"
      "VERTEX 0 1 0\r\nENDLOOP\r\nENDFACET\r\nENDSOLID a\r\nsolid b\n" +
      ascii_facet("0 0 5", "1 0 5", "+1.5e0 1 5") + "endsolid\n";
  const auto mesh = parse_stl(text, "cases.stl");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 2u);
  EXPECT_EQ(mesh->vertices_mm.back(), (Vec3{1.5, 1, 5}));
}

TEST(ParseStl, AsciiNormalMayBeNanButCoordinatesMayNot) {
  const std::string facet =
      "facet normal nan nan nan\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\n";
  EXPECT_TRUE(parse_stl("solid s\n" + facet + "endsolid s\n", "nan_normal.stl").ok());
}

class ParseStlBadCoordinate : public ::testing::TestWithParam<std::string> {};

TEST_P(ParseStlBadCoordinate, IsInvalidArgumentNamingLineAndToken) {
  const std::string text = "solid s\n" + ascii_facet("0 0 0", "1 " + GetParam() + " 0", "0 1 0") + "endsolid s\n";
  const auto mesh = parse_stl(text, "bad.stl");
  expect_invalid(mesh, "STL 'bad.stl' line 5: '" + GetParam() + "'");
}

INSTANTIATE_TEST_SUITE_P(Tokens, ParseStlBadCoordinate,
                         ::testing::Values("nan", "inf", "-inf", "5abc", "1e999", "0x10", "1,5", "--1"));

TEST(ParseStl, BinaryNanCoordinateIsInvalidArgumentNamingTheFacet) {
  const float nan = std::nanf("");
  const auto mesh =
      parse_stl(binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {nan, 0, 0}, {0, 0, 1}}}}), "nan.stl");
  expect_invalid(mesh, "binary STL 'nan.stl' facet 2 corner 2 has a non-finite coordinate");
}

TEST(ParseStl, BinaryInfiniteCoordinateIsInvalidArgument) {
  const float inf = INFINITY;
  expect_invalid(parse_stl(binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, -inf}}}}), "inf.stl"), "non-finite");
}

TEST(ParseStl, TruncatedBinaryIsInvalidArgumentWithBothSizes) {
  std::string bytes = binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}}});
  bytes.resize(bytes.size() - 20);
  expect_invalid(parse_stl(bytes, "cut.stl"),
                 "binary STL 'cut.stl' is truncated or corrupt: its header announces 2 triangles (184 bytes) but the "
                 "file has 164 bytes");
}

TEST(ParseStl, HugeFacetCountInASmallFileIsRefusedBeforeAllocating) {
  std::string bytes = binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}});
  const uint32_t huge = 0xffffffffu;  // 214 GB of facets announced; a reservation would throw
  std::memcpy(bytes.data() + 80, &huge, 4);
  expect_invalid(parse_stl(bytes, "huge.stl"), "announces 4294967295 triangles");
}

TEST(ParseStl, ShorterThanTheBinaryHeaderIsInvalidArgument) {
  expect_invalid(parse_stl("abc", "tiny.stl"), "truncated: 3 bytes, less than the 84-byte header");
  expect_invalid(parse_stl("", "empty.stl"), "0 bytes");
}

TEST(ParseStl, AsciiGrammarErrorsNameTheLineAndWhatWasExpected) {
  expect_invalid(parse_stl("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n", "short.stl"),
                 "STL 'short.stl' line 4: 'vertex' takes 3 values, found 2");
  expect_invalid(parse_stl("solid x\nfacet normal 0 0 1\nvertex 0 0 0\n", "loop.stl"),
                 "line 3: expected 'outer loop', found 'vertex'");
  expect_invalid(parse_stl("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                           "endfacet\n",
                           "endloop.stl"),
                 "line 7: expected 'endloop', found 'endfacet'");
  expect_invalid(parse_stl("solid x\ncolor 1 0 0\n", "color.stl"), "expected 'facet normal' or 'endsolid'");
  expect_invalid(parse_stl("solid x\n" + ascii_facet("0 0 0", "1 0 0", "0 1 0"), "noend.stl"),
                 "STL 'noend.stl' ends (line 8) where 'facet normal' or 'endsolid' was expected");
  expect_invalid(parse_stl("solid x\nendsolid x\ngarbage\n", "after.stl"), "line 3: expected 'solid', found 'garbage'");
}

}  // namespace
}  // namespace soiq
