// Uploads, listing, download, deletion and conversion through a real soiqd and the client library.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/base/run_length_volume.h"
#include "core/geometry/primitives.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/voxelize_1d.h"
#include "tests/integration/service_fixture.h"

namespace soiq::testing {
namespace {

using v1::Structure;

TEST_F(ServiceTest, UploadsEveryMeshFormatAndDownloadsTheSameSurface) {
  const TriangleMesh sphere = uv_sphere({10, -5, 3}, 12, 24, 48);
  for (const std::string ext : {"stl", "obj", "ply", "vtk", "vtp"}) {
    SCOPED_TRACE(ext);
    Result<v1::UploadSurfaceResponse> r = upload(sphere, "P1", "S1", "ball_" + ext, "", ext);
    ASSERT_TRUE(r.ok()) << r.status().to_string();
    EXPECT_GT(r->structure().id(), 0);
    EXPECT_EQ(r->structure().triangle_count(), int64_t(sphere.triangles.size()));
    // The bounds agree with the mesh (STL stores float32: 1e-5 mm).
    EXPECT_NEAR(r->structure().bounds_mm(0), 10 - 12, 1e-4);
    EXPECT_NEAR(r->structure().bounds_mm(5), 3 + 12, 1e-4);

    const std::string out = dir_.file("down_" + ext + ".vtp");
    v1::DownloadSurfaceRequest d;
    d.set_id(r->structure().id());
    Result<int64_t> bytes = client_->download_surface(d, out);
    ASSERT_TRUE(bytes.ok()) << bytes.status().to_string();
    Result<TriangleMesh> back = read_mesh(out);
    ASSERT_TRUE(back.ok()) << back.status().to_string();
    ASSERT_EQ(back->triangles.size(), sphere.triangles.size());
  }
  v1::ListStructuresRequest list;
  list.set_patient_id("P1");
  Result<v1::ListStructuresResponse> all = client_->list_structures(list);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->structures_size(), 5);
}

TEST_F(ServiceTest, TheSameMeshTwiceIsStoredOnce) {
  const TriangleMesh m = uv_sphere({0, 0, 0}, 8, 16, 32);
  Result<v1::UploadSurfaceResponse> a = upload(m, "P1", "S1", "a", "", "vtp");
  Result<v1::UploadSurfaceResponse> b = upload(m, "P2", "S2", "b", "", "vtp");
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_FALSE(a->surface_already_stored());
  EXPECT_TRUE(b->surface_already_stored());
  EXPECT_EQ(a->structure().surface_sha256(), b->structure().surface_sha256());
  EXPECT_NE(a->structure().id(), b->structure().id());
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->structures(), 2);
  EXPECT_EQ(info->surfaces(), 1);
  EXPECT_EQ(info->patients(), 2);
}

TEST_F(ServiceTest, AMeshOverFourMebibytesUploadsWhole) {
  // ~200k triangles as binary STL: 50 bytes each, ~10 MB, far over gRPC's 4 MiB message limit.
  const TriangleMesh big = uv_sphere_with_triangles({0, 0, 0}, 40, 200'000);
  const std::string path = write_mesh_file(big, "stl");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  ASSERT_GT(int64_t(in.tellg()), int64_t(4) << 20);
  Result<v1::UploadSurfaceResponse> r = client_->upload_surface(surface_header("P", "S", "big", ""), path);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->structure().triangle_count(), int64_t(big.triangles.size()));
}

TEST_F(ServiceTest, GetListAndDeleteStructuresAndPatients) {
  ASSERT_TRUE(upload(uv_sphere({0, 0, 0}, 5, 12, 24), "P1", "S1", "Hippocampus", "L").ok());
  ASSERT_TRUE(upload(uv_sphere({30, 0, 0}, 5, 12, 24), "P1", "S1", "Hippocampus", "R").ok());
  ASSERT_TRUE(upload(uv_sphere({0, 0, 0}, 6, 12, 24), "P2", "S2", "Amygdala", "L").ok());

  v1::ListStructuresRequest by_name;
  by_name.set_name_glob("hippo*");  // case-insensitive
  Result<v1::ListStructuresResponse> hippo = client_->list_structures(by_name);
  ASSERT_TRUE(hippo.ok());
  ASSERT_EQ(hippo->structures_size(), 2);

  Result<v1::Patient> p1 = client_->get_patient("P1");
  ASSERT_TRUE(p1.ok());
  EXPECT_EQ(p1->structure_count(), 2);
  Result<v1::Study> s1 = client_->get_study("S1");
  ASSERT_TRUE(s1.ok());
  EXPECT_EQ(s1->patient_id(), "P1");

  Result<v1::DeleteResponse> del = client_->delete_structure(hippo->structures(0).id());
  ASSERT_TRUE(del.ok());
  EXPECT_EQ(del->structures_deleted(), 1);
  Result<Structure> gone = client_->get_structure(hippo->structures(0).id());
  ASSERT_FALSE(gone.ok());
  EXPECT_EQ(gone.status().code(), StatusCode::kNotFound);

  Result<v1::DeleteResponse> dp = client_->delete_patient("P1");
  ASSERT_TRUE(dp.ok());
  EXPECT_EQ(dp->structures_deleted(), 1);
  EXPECT_EQ(client_->get_patient("P1").status().code(), StatusCode::kNotFound);
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->structures(), 1);
  EXPECT_EQ(info->surfaces(), 1);  // the deleted surfaces' blobs went with them
}

TEST_F(ServiceTest, ConversionEqualsTheOfflineOneVoxelForVoxel) {
  const TriangleMesh t = torus({3.3, -2.1, 7.7}, 14, 5, 64, 32);
  Result<v1::UploadSurfaceResponse> up = upload(t, "P", "S", "torus", "", "vtp");
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  for (double spacing : {1.0, 0.7}) {
    SCOPED_TRACE(spacing);
    // Offline: the same mesh on the same grid (what `soiq convert --spacing` does).
    Result<ImageGeometry> g = grid_around(t, {spacing, spacing, spacing}, 2);
    ASSERT_TRUE(g.ok());
    Result<Voxelization> offline = voxelize_1d(t, *g);
    ASSERT_TRUE(offline.ok());

    v1::ConvertRequest req;
    req.set_structure_id(up->structure().id());
    req.mutable_grid()->set_spacing_mm(spacing);
    req.set_encoding(v1::RUNS);
    RunLengthVolume served;
    served.geometry = *g;
    std::vector<std::vector<soiq::Run>> lines(size_t(g->dims[1] * g->dims[2]));
    client::ConvertHandlers h;
    h.on_runs = [&](const v1::RunBatch& b) {
      for (int i = 0; i < b.j_size(); ++i)
        lines[size_t(b.j(i) + g->dims[1] * b.k(i))].push_back({b.begin(i), b.end(i)});
      return true;
    };
    Result<v1::ConvertSummary> summary = client_->convert(req, h);
    ASSERT_TRUE(summary.ok()) << summary.status().to_string();
    EXPECT_EQ(summary->voxel_count(), voxel_count(offline->volume));
    served.line_start.push_back(0);
    for (auto& l : lines) {
      served.runs.insert(served.runs.end(), l.begin(), l.end());
      served.line_start.push_back(int64_t(served.runs.size()));
    }
    EXPECT_EQ(served.line_start, offline->volume.line_start);
    EXPECT_EQ(served.runs, offline->volume.runs);

    // The NIfTI encoding holds the same voxels.
    req.set_encoding(v1::NIFTI_GZ);
    std::string nifti;
    client::ConvertHandlers hn;
    hn.on_nifti = [&](std::string_view bytes) {
      nifti.append(bytes);
      return true;
    };
    ASSERT_TRUE(client_->convert(req, hn).ok());
    const std::string path = dir_.file("served.nii.gz");
    std::ofstream(path, std::ios::binary).write(nifti.data(), std::streamsize(nifti.size()));
    Result<Image> img = read_image(path);
    ASSERT_TRUE(img.ok()) << img.status().to_string();
    const Mask m = mask_from_image(*img);
    EXPECT_EQ(from_mask(m).runs, offline->volume.runs);
  }
}

TEST_F(ServiceTest, BadInputGetsTheRightCodeAndNothingIsStored) {
  // Malformed mesh.
  const std::string junk = dir_.file("junk.stl");
  std::ofstream(junk) << "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 nan\n";
  Result<v1::UploadSurfaceResponse> bad = client_->upload_surface(surface_header("P", "S", "junk", ""), junk);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kInvalidArgument) << bad.status().to_string();

  // An open mesh without robust mode; accepted with it.
  TriangleMesh open = uv_sphere({0, 0, 0}, 10, 12, 24);
  open.triangles.pop_back();
  Result<v1::UploadSurfaceResponse> o = upload(open, "P", "S", "open", "", "vtp");
  ASSERT_FALSE(o.ok());
  EXPECT_EQ(o.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(o.status().message().find("robust"), std::string::npos) << o.status().message();
  Result<v1::UploadSurfaceResponse> orob = upload(open, "P", "S", "open", "", "vtp", /*robust=*/true);
  ASSERT_TRUE(orob.ok()) << orob.status().to_string();
  EXPECT_TRUE(orob->structure().robust());

  // Unknown ids.
  EXPECT_EQ(client_->get_structure(987654).status().code(), StatusCode::kNotFound);
  EXPECT_NE(client_->get_structure(987654).status().message().find("987654"), std::string::npos);
  EXPECT_EQ(client_->get_patient("nobody").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(client_->delete_structure(987654).status().code(), StatusCode::kNotFound);

  // Bad demographics.
  v1::UploadSurfaceHeader h = surface_header("P", "S", "x", "left");
  Result<v1::UploadSurfaceResponse> lat =
      client_->upload_surface(h, write_mesh_file(uv_sphere({0, 0, 0}, 5, 8, 16), "stl"));
  EXPECT_EQ(lat.status().code(), StatusCode::kInvalidArgument);

  // Unknown feature.
  v1::FeaturesRequest f;
  f.set_structure_id(orob->structure().id());
  f.add_features("roundness");
  Result<v1::FeaturesResponse> fr = client_->compute_features(f);
  EXPECT_EQ(fr.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(fr.status().message().find("roundness"), std::string::npos);

  // A grid over the limit (0.01 mm around a 20 mm sphere: 8e9 voxels).
  v1::ConvertRequest c;
  c.set_structure_id(orob->structure().id());
  c.mutable_grid()->set_spacing_mm(0.01);
  Result<v1::ConvertSummary> cs = client_->convert(c, {});
  EXPECT_EQ(cs.status().code(), StatusCode::kResourceExhausted) << cs.status().to_string();

  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->structures(), 1);  // only the robust upload
}

TEST_F(ServiceTest, AnUploadOverTheLimitIsRefusedAndNothingIsStored) {
  start({"--max-upload-bytes", "100000"});
  client_ = std::make_unique<client::Client>(connect());
  const TriangleMesh m = uv_sphere_with_triangles({0, 0, 0}, 20, 20'000);  // ~1 MB as STL
  Result<v1::UploadSurfaceResponse> r = upload(m, "P", "S", "big");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted);
  EXPECT_NE(r.status().message().find("100000"), std::string::npos) << r.status().message();
  EXPECT_EQ(client_->server_info()->structures(), 0);
}

}  // namespace
}  // namespace soiq::testing
