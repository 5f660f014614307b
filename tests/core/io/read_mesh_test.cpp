#include "core/io/read_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/io/write_mesh.h"
#include "core/mesh_defects.h"
#include "tests/core/io/io_test_files.h"
#include "tests/core/io/mesh_test_shapes.h"

namespace soiq {
namespace {

using testing_io::write_bytes;

// A binary STL of `triangles` facets (normal zero), vertices as given.
std::string binary_stl(const std::vector<std::array<std::array<float, 3>, 3>>& triangles) {
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

TEST(ReadMesh, NanVerticesAreReadAndCountedByMeshDefects) {
  const float nan = std::nanf("");
  const std::string path =
      write_bytes("nan.stl", binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {nan, 0, 0}, {0, 0, 1}}}}));
  const auto mesh = read_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  EXPECT_EQ(mesh->triangles.size(), 2u);
  EXPECT_GE(mesh_defects(*mesh).nonfinite_vertices, 1);
}

TEST(ReadMesh, EmptyFileIsInvalidArgument) {
  for (const char* name : {"empty.stl", "empty.obj", "empty.ply", "empty.vtk", "empty.vtp"}) {
    const auto mesh = read_mesh(write_bytes(name, ""));
    EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument) << name;
    EXPECT_NE(mesh.status().message().find("is empty"), std::string::npos) << mesh.status().message();
  }
}

TEST(ReadMesh, TruncatedBinaryStlIsInvalidArgument) {
  std::string bytes = binary_stl({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}}});
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

TEST(ReadMesh, ObjRelativeIndicesAreRefusedNotMisread) {
  // vtkOBJReader would read -1 as an absolute index; refuse instead of building a wrong mesh.
  const auto mesh = read_mesh(write_bytes("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("relative (negative) face indices are not supported"), std::string::npos)
      << mesh.status().message();
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
  const auto mesh = read_mesh(write_bytes("mesh.off", "OFF\n"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mesh.status().message().find("unknown mesh extension '.off'"), std::string::npos);
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
