// Uploaded bytes to core objects and back, on their own: a surface written by surface_bytes parses
// back to the same mesh, RAS is LPS with x and y negated, an inward closed mesh is turned outward,
// an open one needs robust mode, and malformed bytes or a header naming a server file are refused.
#include "server/app/uploaded_files.h"

#include <gtest/gtest.h>

#include "core/geometry/mesh_defects.h"
#include "core/geometry/primitives.h"

namespace soiq::server {
namespace {

TriangleMesh open_box() {
  TriangleMesh m = box({0, 0, 0}, {10, 10, 10});
  m.triangles.pop_back();
  return m;
}

TEST(UploadedFiles, ASurfaceReadsBackAsWrittenInEveryWritableFormat) {
  const TriangleMesh m = box({1, 2, 3}, {11, 7, 9});
  for (const char* format : {"stl", "obj", "ply", "vtk", "vtp"}) {  // OFF is read, never written
    Result<std::string> bytes = surface_bytes(m, format, false);
    ASSERT_TRUE(bytes.ok()) << format << ": " << bytes.status().to_string();
    Result<ParsedSurface> back = parse_surface(*bytes, format, false, false, "box");
    ASSERT_TRUE(back.ok()) << format << ": " << back.status().to_string();
    EXPECT_EQ(back->mesh.triangles.size(), m.triangles.size()) << format;
    EXPECT_NEAR(signed_volume_mm3(back->mesh), 10 * 5 * 6, 1e-9) << format;
  }
}

TEST(UploadedFiles, RasCoordinatesArriveAsLps) {
  const TriangleMesh m = box({1, 2, 3}, {11, 7, 9});
  Result<std::string> ras = surface_bytes(m, "stl", true);
  ASSERT_TRUE(ras.ok());
  Result<ParsedSurface> back = parse_surface(*ras, "stl", true, false, "box");
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (const Vec3& v : back->mesh.vertices_mm)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
  EXPECT_EQ(lo[0], 1);
  EXPECT_EQ(hi[1], 7);
  EXPECT_EQ(hi[2], 9);
  // Read as LPS, the same bytes are the mirror image.
  Result<ParsedSurface> mirrored = parse_surface(*ras, "stl", false, false, "box");
  ASSERT_TRUE(mirrored.ok());
  double min_x = 1e9;
  for (const Vec3& v : mirrored->mesh.vertices_mm) min_x = std::min(min_x, v[0]);
  EXPECT_EQ(min_x, -11);
}

TEST(UploadedFiles, AnInwardClosedSurfaceIsTurnedOutward) {
  Result<std::string> bytes = surface_bytes(flipped(box({0, 0, 0}, {2, 3, 4})), "ply", false);
  ASSERT_TRUE(bytes.ok());
  Result<ParsedSurface> back = parse_surface(*bytes, "ply", false, false, "inward");
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  EXPECT_NEAR(signed_volume_mm3(back->mesh), 24, 1e-12);
}

TEST(UploadedFiles, AnOpenSurfaceNeedsRobustModeAndSaysSo) {
  Result<std::string> bytes = surface_bytes(open_box(), "stl", false);
  ASSERT_TRUE(bytes.ok());
  Result<ParsedSurface> plain = parse_surface(*bytes, "stl", false, false, "hippo_L");
  EXPECT_EQ(plain.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(plain.status().message().find("hippo_L"), std::string::npos) << plain.status().message();
  EXPECT_NE(plain.status().message().find("robust"), std::string::npos) << plain.status().message();
  Result<ParsedSurface> robust = parse_surface(*bytes, "stl", false, true, "hippo_L");
  ASSERT_TRUE(robust.ok()) << robust.status().to_string();
  EXPECT_GT(robust->defects.boundary_edges, 0);
}

TEST(UploadedFiles, MalformedBytesAreInvalidArgumentNamingTheUpload) {
  for (const char* format : {"stl", "obj", "ply", "off", "vtk", "vtp"}) {
    Result<ParsedSurface> r = parse_surface("this is not a mesh", format, false, false, "thalamus_R");
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << format;
    EXPECT_NE(r.status().message().find("thalamus_R"), std::string::npos) << format << ": " << r.status().message();
  }
  EXPECT_EQ(parse_surface("solid x", "dxf", false, false, "x").status().code(), StatusCode::kInvalidArgument);
}

TEST(UploadedFiles, AnImageHeaderNamingADataFileIsRefusedUnread) {
  const std::string nrrd =
      "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: raw\nendian: little\n"
      "data file: /etc/passwd\n\n";
  Result<Image> r = parse_image(nrrd, "nrrd", "img", {});
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(r.status().message().find("root:"), std::string::npos);
}

}  // namespace
}  // namespace soiq::server
