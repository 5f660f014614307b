#include "core/io/read_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/geometry/mesh_defects.h"
#include "core/io/write_mesh.h"
#include "tests/core/io/io_test_files.h"
#include "tests/core/io/mesh_test_shapes.h"

namespace soiq {
namespace {

using testing_io::write_bytes;

// A binary STL of `triangles` facets (normal zero), vertices as given.
std::string binary_stl_of(const std::vector<std::array<std::array<float, 3>, 3>>& triangles) {
  std::string bytes(80, ' ');
  const uint32_t n = uint32_t(triangles.size());
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : triangles) {
    const float normal[3] = {0, 0, 0};
    bytes.append(reinterpret_cast<const char*>(normal), 12);
    for (const auto& v : t) bytes.append(reinterpret_cast<const char*>(v.data()), 12);
    bytes.append(2, '\0');
  }
  return bytes;
}

const char* kTetraObj =
    "# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(ReadMesh, ObjTetrahedronIsClosed) {
  const auto mesh = read_mesh(write_bytes("tetra.obj", kTetraObj));
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->vertices_mm.size(), 4u);
  EXPECT_EQ(mesh->triangles.size(), 4u);
  EXPECT_TRUE(mesh_defects(*mesh).closed());
}

TEST(ReadMesh, QuadsAreTriangulatedAndLinesIgnored) {
  const auto mesh = read_mesh(write_bytes("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nl 1 3\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 2u);
}

TEST(ReadMesh, AsciiStlWithSharedCornersIsIndexed) {
  const auto mesh = read_mesh(write_bytes("two.stl",
                                          "solid two\n"
                                          "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                          "endloop\nendfacet\n"
                                          "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n"
                                          "endloop\nendfacet\nendsolid two\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 2u);
  EXPECT_EQ(mesh->vertices_mm.size(), 4u);  // merged
}

TEST(ReadMesh, BinaryStlBoxIsMergedIntoAWatertightMesh) {
  const std::string path = testing_io::scratch_path("box.stl");
  ASSERT_TRUE(write_mesh(testing_io::awkward_box(), path).ok());
  const auto mesh = read_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->vertices_mm.size(), 8u);
  EXPECT_TRUE(mesh_defects(*mesh).closed());
}

TEST(ReadMesh, RasFlagNegatesXAndY) {
  const auto lps = read_mesh(write_bytes("ras.obj", kTetraObj));
  const auto ras = read_mesh(testing_io::scratch_path("ras.obj"), /*ras=*/true);
  ASSERT_TRUE(lps.ok() && ras.ok());
  for (size_t i = 0; i < lps->vertices_mm.size(); ++i) {
    const Vec3 p = lps->vertices_mm[i];
    EXPECT_EQ(ras->vertices_mm[i], (Vec3{-p[0], -p[1], p[2]}));
  }
}

TEST(ReadMesh, NanVertexInBinaryStlIsInvalidArgumentNamingTheFacet) {
  // VTK passed NaN corners through and validate_mesh refused them later without saying where; the
  // parser refuses them at once, naming the facet.
  const float nan = std::nanf("");
  const std::string path = write_bytes(
      "nan.stl", binary_stl_of({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {nan, 0, 0}, {0, 0, 1}}}}));
  const auto mesh = read_mesh(path);
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("facet 2 corner 2 has a non-finite coordinate"), std::string::npos)
      << mesh.status().message();
}

TEST(ReadMesh, ObjNanAndTrailingGarbageAreInvalidArgumentNotZeroAndFive) {
  // vtkOBJReader read "nan" as 0 and "5abc" as 5, silently.
  for (const std::string token : {"nan", "5abc"}) {
    const auto mesh = read_mesh(write_bytes("garbage_number.obj", "v 0 0 0\nv 1 0 0\nv 0 " + token + " 0\nf 1 2 3\n"));
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << token;
    EXPECT_NE(mesh.status().message().find("line 3: '" + token + "'"), std::string::npos) << mesh.status().message();
  }
}

TEST(ReadMesh, EmptyFileIsInvalidArgument) {
  for (const char* name : {"empty.stl", "empty.obj", "empty.ply", "empty.off", "empty.vtk", "empty.vtp"}) {
    const auto mesh = read_mesh(write_bytes(name, ""));
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << name;
    EXPECT_NE(mesh.status().message().find("is empty"), std::string::npos) << mesh.status().message();
  }
}

TEST(ReadMesh, TruncatedBinaryStlIsInvalidArgument) {
  std::string bytes = binary_stl_of({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}}});
  bytes.resize(bytes.size() - 20);
  const std::string path = write_bytes("cut.stl", bytes);
  const auto mesh = read_mesh(path);
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("truncated"), std::string::npos) << mesh.status().message();
  EXPECT_NE(mesh.status().message().find("announces 2 triangles"), std::string::npos) << mesh.status().message();
  EXPECT_NE(mesh.status().message().find(path), std::string::npos);
}

TEST(ReadMesh, StlShorterThanItsHeaderIsInvalidArgument) {
  const auto mesh = read_mesh(write_bytes("tiny.stl", "abc"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("84-byte header"), std::string::npos) << mesh.status().message();
}

TEST(ReadMesh, MalformedAsciiStlIsInvalidArgument) {
  const auto mesh = read_mesh(write_bytes("bad_ascii.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << mesh.status().to_string();
}

TEST(ReadMesh, ObjFaceIndexOutOfRangeIsInvalidArgument) {
  const auto mesh = read_mesh(write_bytes("oob.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("face index 7 is out of range"), std::string::npos) << mesh.status().message();
  EXPECT_NE(mesh.status().message().find("line 4"), std::string::npos);
}

TEST(ReadMesh, ObjNegativeIndexBeyondStartIsInvalidArgument) {
  const auto mesh = read_mesh(write_bytes("neg.obj", "v 0 0 0\nv 1 0 0\nf 1 2 -3\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("face index -3 is out of range"), std::string::npos)
      << mesh.status().message();
}

TEST(ReadMesh, ObjRelativeIndicesAreResolved) {
  // vtkOBJReader read -1 as an absolute index, so they used to be refused; soiq's parser resolves
  // them against the vertices defined so far.
  const auto mesh = read_mesh(write_bytes("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles, (std::vector<std::array<int32_t, 3>>{{0, 1, 2}}));
}

TEST(ReadMesh, ObjTextureIndexOutOfRangeIsInvalidArgument) {
  const auto mesh = read_mesh(write_bytes("vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/9\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("texture coordinate"), std::string::npos) << mesh.status().message();
}

TEST(ReadMesh, PlyFaceIndexOutOfRangeIsInvalidArgument) {
  const auto mesh = read_mesh(write_bytes("oob.ply",
                                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                          "property float y\nproperty float z\nelement face 1\n"
                                          "property list uchar int vertex_indices\nend_header\n"
                                          "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("out of range"), std::string::npos) << mesh.status().message();
}

TEST(ReadMesh, PlyVertexLineWithTooFewValuesIsInvalidArgumentNotACrash) {
  // vtkPLYReader segfaulted on this file and took the server down.
  const auto mesh = read_mesh(write_bytes("short_line.ply",
                                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                          "property float y\nproperty float z\nelement face 1\n"
                                          "property list uchar int vertex_indices\nend_header\n"
                                          "0 0 0\n1 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("line 11: vertex has 2 values, the header declares 3"), std::string::npos)
      << mesh.status().message();
}

TEST(ReadMesh, AsciiLegacyVtk51WithAttributesIsRead) {
  const auto mesh = read_mesh(write_bytes("tetra51.vtk",
                                          "# vtk DataFile Version 5.1\ntetra\nASCII\nDATASET POLYDATA\n"
                                          "POINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nMETADATA\nINFORMATION 0\n\n"
                                          "POLYGONS 5 12\nOFFSETS vtktypeint64\n0 3 6 9 12\n"
                                          "CONNECTIVITY vtktypeint64\n0 2 1 0 1 3 0 3 2 1 2 3\n"
                                          "POINT_DATA 4\nSCALARS s float 1\nLOOKUP_TABLE default\n1 2 3 4\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 4u);
  EXPECT_TRUE(mesh_defects(*mesh).closed());
}

TEST(ReadMesh, LegacyVtkCellIndexOutOfRangeIsInvalidArgument) {
  const auto mesh = read_mesh(write_bytes("oob.vtk",
                                          "# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\n"
                                          "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 9\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("point index 9 is out of range"), std::string::npos)
      << mesh.status().message();
}

TEST(ReadMesh, GarbagePlyVtkAndVtpAreInvalidArgument) {
  for (const char* name : {"garbage.ply", "garbage.vtk", "garbage.vtp"}) {
    const auto mesh = read_mesh(write_bytes(name, "this is not a mesh file\n\x01\x02\x03"));
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << name;
    EXPECT_NE(mesh.status().message().find(name), std::string::npos) << mesh.status().message();
  }
}

TEST(ReadMesh, ObjWithoutFacesHasNoTriangles) {
  const auto mesh = read_mesh(write_bytes("points.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("contains no triangles"), std::string::npos) << mesh.status().message();
}

TEST(ReadMesh, UnknownExtensionIsInvalidArgument) {
  const auto mesh = read_mesh(write_bytes("mesh.xyz", "OFF\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("unknown mesh extension '.xyz'"), std::string::npos);
}

TEST(ReadMesh, OffTetrahedronIsClosed) {
  const auto mesh = read_mesh(write_bytes("tetra.off",
                                          "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                          "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_TRUE(mesh_defects(*mesh).closed());
}

TEST(ReadMesh, MissingFileIsNotFound) {
  for (const char* name : {"missing.stl", "missing.obj", "missing.vtp"}) {
    const auto mesh = read_mesh(testing_io::scratch_path(name));
    EXPECT_EQ(mesh.status().code(), StatusCode::kNotFound) << name;
    EXPECT_NE(mesh.status().message().find("does not exist"), std::string::npos);
  }
}

}  // namespace
}  // namespace soiq

namespace soiq {
namespace {

class ReadMeshHostile : public ::testing::TestWithParam<std::string> {};

TEST_P(ReadMeshHostile, TruncatedFilesFailCleanlyOrReadButNeverCrash) {
  const std::string full = testing_io::scratch_path("whole" + GetParam());
  ASSERT_TRUE(write_mesh(testing_io::awkward_box(), full).ok());
  std::ifstream in(full, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (size_t cut = 1; cut < bytes.size(); cut += std::max<size_t>(1, bytes.size() / 37)) {
    const auto mesh = read_mesh(write_bytes("cut" + GetParam(), bytes.substr(0, cut)));
    if (!mesh.ok()) {
      EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << cut << ": " << mesh.status().to_string();
    } else {
      // A reader may stop early and still hold whole triangles; their indices must be valid.
      EXPECT_EQ(mesh_defects(*mesh).bad_indices, 0) << cut;
    }
  }
}

TEST_P(ReadMeshHostile, FlippedBytesFailCleanlyOrReadButNeverCrash) {
  const std::string full = testing_io::scratch_path("flip_src" + GetParam());
  ASSERT_TRUE(write_mesh(testing_io::awkward_box(), full).ok());
  std::ifstream in(full, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint32_t state = 12345;  // fixed LCG: the same corruptions on every run
  for (int round = 0; round < 40; ++round) {
    std::string bad = bytes;
    for (int k = 0; k < 4; ++k) {
      state = state * 1664525u + 1013904223u;
      bad[state % bad.size()] = char(state >> 24);
    }
    const auto mesh = read_mesh(write_bytes("flip" + GetParam(), bad));
    if (!mesh.ok()) {
      EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << round << ": " << mesh.status().to_string();
    } else {
      EXPECT_EQ(mesh_defects(*mesh).bad_indices, 0) << round;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, ReadMeshHostile, ::testing::Values(".stl", ".obj", ".ply", ".vtk", ".vtp"),
                         [](const auto& info) { return info.param.substr(1); });

}  // namespace
}  // namespace soiq
