// soiq's own PLY parser: VTK's writer and reader are the oracle on well-formed files (ASCII and
// both byte orders); hostile inputs each give one INVALID_ARGUMENT line, among them the vertex
// line with too few values that crashed vtkPLYReader.
#include "core/io/parse_ply.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
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

using Triangles = std::vector<std::array<int32_t, 3>>;

// Appends `value` in the given byte order.
template <typename T>
void put(std::string& out, T value, bool big_endian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  out.append(raw, sizeof(T));
}

const char* kTriangleHeader =
    "ply\nformat ascii 1.0\ncomment one triangle\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

struct PlyVariant {
  const char* name;
  bool ascii;
  bool big_endian;
};

class ParsePlyOracle : public ::testing::TestWithParam<PlyVariant> {};

TEST_P(ParsePlyOracle, FromVtkWriterEqualsVtkReaderVertexForVertex) {
  for (const TriangleMesh& shape : {testing_io::awkward_box(), uv_sphere({4, -2, 9}, 6, 10, 20)}) {
    const std::string path = testing_io::scratch_path(std::string("oracle_") + GetParam().name + ".ply");
    ASSERT_TRUE(testing_io::write_ply_with_vtk(shape, path, GetParam().ascii, GetParam().big_endian));
    const auto ours = parse_ply(file_bytes(path), "oracle.ply");
    ASSERT_TRUE(ours.ok()) << ours.status().to_string();
    const TriangleMesh vtk = testing_io::read_with_vtk(path);
    // vtkPLYWriter writes float32 and vtkPLYReader keeps float32: binary files agree exactly; ASCII
    // ones agree once ours (the written decimal as a double) is rounded to float32.
    EXPECT_EQ(GetParam().ascii ? testing_io::rounded_to_float(*ours).vertices_mm : ours->vertices_mm, vtk.vertices_mm);
    EXPECT_EQ(ours->triangles, vtk.triangles);
    EXPECT_TRUE(mesh_defects(*ours).closed());
  }
}

INSTANTIATE_TEST_SUITE_P(Variants, ParsePlyOracle,
                         ::testing::Values(PlyVariant{"ascii", true, false}, PlyVariant{"little", false, false},
                                           PlyVariant{"big", false, true}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(ParsePly, WriteMeshBinaryFileIsReadBackExactly) {
  const std::string path = testing_io::scratch_path("write_mesh.ply");
  ASSERT_TRUE(write_mesh(testing_io::awkward_box(), path).ok());
  const auto ours = parse_ply(file_bytes(path), "write_mesh.ply");
  ASSERT_TRUE(ours.ok()) << ours.status().to_string();
  EXPECT_EQ(ours->vertices_mm, testing_io::rounded_to_float(testing_io::awkward_box()).vertices_mm);
  EXPECT_EQ(ours->triangles, testing_io::awkward_box().triangles);
}

TEST(ParsePly, BigEndianDoublesWithExtraPropertiesAndElementsAreReadExactly) {
  const bool big = true;
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty uchar red\nproperty double x\n"
      "property double y\nproperty double z\nproperty list uchar float texture\nelement face 2\n"
      "property int flags\nproperty list ushort uint vertex_index\nelement material 1\nproperty short m\n"
      "end_header\n";
  const double coords[4][3] = {{0.1, 0.2, 0.3}, {1e-300, 2, 3}, {-7.25, 1e300, 0}, {1, 1, 1}};
  for (const auto& c : coords) {
    put<uint8_t>(bytes, 255, big);
    for (const double v : c) put<double>(bytes, v, big);
    put<uint8_t>(bytes, 2, big);
    put<float>(bytes, std::nanf(""), big);  // skipped values may be NaN
    put<float>(bytes, 0.5f, big);
  }
  put<int32_t>(bytes, -1, big);
  put<uint16_t>(bytes, 3, big);
  for (const uint32_t i : {0u, 1u, 2u}) put<uint32_t>(bytes, i, big);
  put<int32_t>(bytes, 7, big);
  put<uint16_t>(bytes, 4, big);
  for (const uint32_t i : {0u, 2u, 3u, 1u}) put<uint32_t>(bytes, i, big);
  put<int16_t>(bytes, 5, big);
  const auto mesh = parse_ply(bytes, "big.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  ASSERT_EQ(mesh->vertices_mm.size(), 4u);
  for (int v = 0; v < 4; ++v) EXPECT_EQ(mesh->vertices_mm[v], (Vec3{coords[v][0], coords[v][1], coords[v][2]}));
  EXPECT_EQ(mesh->triangles, (Triangles{{0, 1, 2}, {0, 2, 3}, {0, 3, 1}}));
}

TEST(ParsePly, AsciiWithCrLfCommentsAndIntegerCoordinatesIsRead) {
  const auto mesh = parse_ply(
      "ply\r\nformat ascii 1.0\r\nobj_info x\r\nelement vertex 3\r\nproperty int x\r\nproperty int y\r\n"
      "property int z\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
      "0 0 0\r\n1 0 0\r\n\r\n0 1 0\r\n3 0 1 2\r\n",
      "crlf.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles, (Triangles{{0, 1, 2}}));
}

TEST(ParsePly, VertexLineWithTooFewValuesIsInvalidArgumentNotACrash) {
  // vtkPLYReader segfaulted here and took the server down.
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "short.ply"),
                 "PLY 'short.ply' line 12: vertex has 2 values, the header declares 3");
}

TEST(ParsePly, VertexLineWithTooManyValuesIsInvalidArgument) {
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "long.ply"),
                 "line 11: vertex has 4 values, the header declares 3");
}

TEST(ParsePly, FaceLineShorterThanItsCountIsInvalidArgument) {
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "face.ply"),
                 "line 14: face has 4 values, the header and its list counts declare 5");
}

class ParsePlyBadCoordinate : public ::testing::TestWithParam<std::string> {};

TEST_P(ParsePlyBadCoordinate, IsInvalidArgumentNamingLineAndToken) {
  const auto mesh =
      parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 " + GetParam() + " 0\n0 1 0\n3 0 1 2\n", "bad.ply");
  expect_invalid(mesh, "PLY 'bad.ply' line 12: '" + GetParam() + "'");
}

INSTANTIATE_TEST_SUITE_P(Tokens, ParsePlyBadCoordinate, ::testing::Values("nan", "inf", "5abc", "1e999", "0,5"),
                         [](const auto& info) { return "case" + std::to_string(info.index); });

TEST(ParsePly, BinaryNanCoordinateIsInvalidArgument) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  for (const float v : {0.0f, std::nanf(""), 0.0f}) put<float>(bytes, v, false);
  expect_invalid(parse_ply(bytes, "nan.ply"), "PLY 'nan.ply' vertex 1 (from 1): coordinate y is not finite");
}

TEST(ParsePly, IntegerValueOutOfItsTypeIsInvalidArgument) {
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n", "uchar.ply"),
                 "line 14: 300 is out of range for uchar");
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", "float.ply"),
                 "line 14: '1.5' is not an integer");
}

TEST(ParsePly, FaceIndexOutOfRangeIsInvalidArgument) {
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "oob.ply"),
                 "PLY 'oob.ply' line 14: face index 5 is out of range (3 vertices)");
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "neg.ply"),
                 "face index -1 is out of range");
}

TEST(ParsePly, BinaryFaceIndexOutOfRangeIsInvalidArgument) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (int k = 0; k < 9; ++k) put<float>(bytes, float(k), false);
  put<uint8_t>(bytes, 3, false);
  for (const int32_t i : {0, 1, 3}) put<int32_t>(bytes, i, false);
  expect_invalid(parse_ply(bytes, "oob.ply"),
                 "PLY 'oob.ply' face 1 (from 1): face index 3 is out of range (3 vertices)");
}

TEST(ParsePly, FaceWithTwoCornersIsInvalidArgument) {
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "two.ply"),
                 "face has 2 corners; a face needs at least 3");
}

TEST(ParsePly, TruncatedBinaryIsInvalidArgument) {
  const std::string path = testing_io::scratch_path("whole.ply");
  ASSERT_TRUE(write_mesh(testing_io::awkward_box(), path).ok());
  const std::string bytes = file_bytes(path);
  for (const size_t cut : {size_t(1), size_t(7), size_t(13), size_t(50)}) {
    const auto mesh = parse_ply(bytes.substr(0, bytes.size() - cut), "cut.ply");
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << cut;
    EXPECT_NE(mesh.status().message().find("truncated"), std::string::npos) << mesh.status().message();
  }
}

TEST(ParsePly, BytesAfterTheLastElementAreInvalidArgument) {
  const std::string path = testing_io::scratch_path("tail.ply");
  ASSERT_TRUE(write_mesh(testing_io::awkward_box(), path).ok());
  expect_invalid(parse_ply(file_bytes(path) + "xyz", "tail.ply"), "has 3 bytes after its last element");
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n5 5 5\n", "extra.ply"),
                 "line 15: data after the last element");
}

TEST(ParsePly, AsciiEndingEarlyIsInvalidArgument) {
  // Long enough for the header's counts, so the size check lets it through to the body.
  expect_invalid(
      parse_ply(std::string(kTriangleHeader) + "0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n", "early.ply"),
      "PLY 'early.ply' ends in element 'vertex' after 2 of 3 items; is it truncated?");
  expect_invalid(parse_ply(std::string(kTriangleHeader) + "0 0 0\n1 0 0\n", "short.ply"),
                 "PLY 'short.ply' is truncated or corrupt: element 'vertex' announces 3 items of at least 6 bytes, "
                 "but the data has 12 bytes");
}

TEST(ParsePly, HugeElementCountsAreRefusedBeforeAllocating) {
  // Reserving 10^18 vertices would throw std::length_error: passing proves nothing was reserved.
  for (const char* format : {"ascii", "binary_little_endian"}) {
    const std::string bytes = std::string("ply\nformat ") + format +
                              " 1.0\nelement vertex 1000000000000000000\nproperty float x\nproperty float y\n"
                              "property float z\nend_header\n0 0 0\n";
    expect_invalid(parse_ply(bytes, "huge.ply"), "element 'vertex' announces 1000000000000000000 items");
  }
  expect_invalid(
      parse_ply(
          std::string(kTriangleHeader).replace(std::string(kTriangleHeader).find("face 1"), 6, "face 99999999999") +
              "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
          "faces.ply"),
      "element 'face' announces 99999999999 items");
}

TEST(ParsePly, MalformedHeadersAreInvalidArgument) {
  const std::string v = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
  expect_invalid(parse_ply("", "empty.ply"), "does not start with the line 'ply'");
  expect_invalid(parse_ply("this is not a mesh", "garbage.ply"), "PLY 'garbage.ply' does not start with");
  expect_invalid(parse_ply("ply\nformat ascii 1.0\n" + v, "noend.ply"), "no 'end_header' line");
  expect_invalid(parse_ply("ply\nformat ascii 2.0\n" + v + "end_header\n", "version.ply"), "line 2: expected 'format");
  expect_invalid(parse_ply("ply\nformat text 1.0\n" + v + "end_header\n", "format.ply"), "unknown format 'text'");
  expect_invalid(parse_ply("ply\n" + v + "end_header\n0 0 0\n", "noformat.ply"), "has no 'format' line");
  expect_invalid(parse_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                           "end_header\n0 0\n",
                           "noz.ply"),
                 "element 'vertex' needs one scalar property 'z'");
  expect_invalid(parse_ply("ply\nformat ascii 1.0\nproperty float x\n", "orphan.ply"),
                 "'property' before any 'element'");
  expect_invalid(parse_ply("ply\nformat ascii 1.0\n" + v + "property float128 w\nend_header\n", "type.ply"),
                 "line 7: expected 'property <type> <name>'");
  expect_invalid(
      parse_ply("ply\nformat ascii 1.0\n" + v + "element face 1\nproperty int flags\nend_header\n", "noindices.ply"),
      "element 'face' needs one 'vertex_indices' list, it has 0");
  expect_invalid(parse_ply("ply\nformat ascii 1.0\nelement vert\x01x 1\n", "ctrl.ply"),
                 "line 3: element name 'vert?x' is not a short printable word");
  expect_invalid(parse_ply("ply\nformat ascii 1.0\n" + v + "element vertex -1\nend_header\n", "negative.ply"),
                 "negative element count -1");
  expect_invalid(parse_ply("ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\n"
                           "end_header\n",
                           "novertex.ply"),
                 "has no 'vertex' element");
}

}  // namespace
}  // namespace soiq
