// soiq's own OFF parser (VTK has no OFF reader to compare with: the expected meshes are counted by
// hand); hostile inputs each give one INVALID_ARGUMENT line.
#include "core/io/parse_off.h"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "core/geometry/mesh_defects.h"
#include "tests/core/io/io_test_files.h"

namespace soiq {
namespace {

using testing_io::expect_invalid;

using Triangles = std::vector<std::array<int32_t, 3>>;

const char* kTetra = "OFF\n# a tetrahedron\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

TEST(ParseOff, TetrahedronIsReadClosed) {
  const auto mesh = parse_off(kTetra, "tetra.off");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->vertices_mm, (std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
  EXPECT_EQ(mesh->triangles, (Triangles{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
  EXPECT_TRUE(mesh_defects(*mesh).closed());
}

TEST(ParseOff, CountsOnTheOffLineAndColouredQuadsAreRead) {
  const auto mesh = parse_off("OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n", "quad.off");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles, (Triangles{{0, 1, 2}, {0, 2, 3}}));
}

TEST(ParseOff, NonFiniteOrMalformedCoordinateIsInvalidArgument) {
  for (const std::string token : {"nan", "inf", "5abc"}) {
    const std::string text = "OFF\n3 1 0\n0 0 0\n1 " + token + " 0\n0 1 0\n3 0 1 2\n";
    expect_invalid(parse_off(text, "bad.off"), "OFF 'bad.off' line 4: '" + token + "'");
  }
}

TEST(ParseOff, IndexOutOfRangeIsInvalidArgument) {
  expect_invalid(parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "oob.off"),
                 "line 6: face index 3 is out of range (3 vertices)");
  expect_invalid(parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "neg.off"), "face index -1 is out of range");
}

TEST(ParseOff, FaceValueCountMustMatchItsCornerCount) {
  expect_invalid(parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "short.off"),
                 "face declares 4 corners and has 3 values");
}

TEST(ParseOff, HugeCountsAreRefusedBeforeAllocating) {
  // Reserving 10^18 vertices would throw std::length_error: passing proves nothing was reserved.
  expect_invalid(parse_off("OFF\n1000000000000000000 1 0\n0 0 0\n", "huge.off"),
                 "announces 1000000000000000000 vertices");
}

TEST(ParseOff, TruncatedAndTrailingDataAreInvalidArgument) {
  const std::string tetra = kTetra;
  expect_invalid(
      parse_off(tetra.substr(0, tetra.size() - 8), "cut.off"),
      "OFF 'cut.off' is truncated or corrupt: it announces 4 vertices and 4 faces, but only 48 bytes follow");
  // Long enough for the counts (a comment pads it), so the missing face is found by reading.
  expect_invalid(parse_off(tetra.substr(0, tetra.size() - 8) + "# padding\n", "short.off"),
                 "OFF 'short.off' ends after 3 of 4 faces; is it truncated?");
  expect_invalid(parse_off(tetra + "3 0 1 2\n", "tail.off"), "line 12: data after the last face");
}

TEST(ParseOff, OtherVariantsAreRefused) {
  expect_invalid(parse_off("COFF\n3 1 0\n", "c.off"), "does not start with the keyword 'OFF' (found 'COFF')");
  expect_invalid(parse_off("", "empty.off"), "does not start with the keyword 'OFF'");
}

}  // namespace
}  // namespace soiq
