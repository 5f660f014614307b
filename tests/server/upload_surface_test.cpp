// The UploadSurface engine on its own, without gRPC: a box's bytes stored as a structure of a real
// SQLite store (the same surface twice is stored once), and malformed bytes, an open surface
// without robust mode and a study of another patient refused with nothing stored.
#include "server/app/upload_surface.h"

#include <gtest/gtest.h>

#include "core/geometry/primitives.h"
#include "server/app/uploaded_files.h"
#include "tests/db/temp_store.h"

namespace soiq::server {
namespace {

using db::testing::contains;
using db::testing::TempDir;

SurfaceUpload surface_upload_of(const std::string& patient, const std::string& study, const std::string& name) {
  SurfaceUpload u;
  u.patient.patient_id = patient;
  u.study.study_uid = study;
  u.study.patient_id = patient;
  u.structure_name = name;
  u.laterality = "L";
  u.format = "stl";
  return u;
}

std::string stl_of(const TriangleMesh& mesh) {
  Result<std::string> bytes = surface_bytes(mesh, "stl", false);
  EXPECT_TRUE(bytes.ok()) << bytes.status().to_string();
  return bytes.ok() ? *bytes : std::string();
}

class UploadSurfaceTest : public ::testing::Test {
 protected:
  int64_t stored_structures() {
    Result<db::Counts> c = store_->counts();
    EXPECT_TRUE(c.ok()) << c.status().to_string();
    return c.ok() ? c->structures : -1;
  }

  TempDir tmp_;
  std::unique_ptr<db::SqliteStore> store_ = db::testing::open_store(tmp_.file("soiq.db"));
  const std::string box_ = stl_of(box({0, 0, 0}, {10, 5, 4}));
};

TEST_F(UploadSurfaceTest, ABoxIsStoredAsAStructureOfItsPatientAndStudy) {
  Result<UploadedSurface> up = upload_surface(*store_, surface_upload_of("P1", "S1", "hippo"), box_);
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  EXPECT_TRUE(up->defects.closed());
  EXPECT_FALSE(up->added.surface_already_stored);
  Result<db::StructureRecord> stored = store_->get_structure(up->added.structure.id);
  ASSERT_TRUE(stored.ok()) << stored.status().to_string();
  EXPECT_EQ(stored->name, "hippo");
  EXPECT_EQ(stored->laterality, "L");
  EXPECT_EQ(stored->study_uid, "S1");
  EXPECT_FALSE(stored->robust);
  EXPECT_EQ(stored->surface.triangle_count, 12);
  EXPECT_EQ(stored->surface.bounds_mm[3], 10);  // min x y z, max x y z
}

TEST_F(UploadSurfaceTest, TheSameSurfaceTwiceIsStoredOnce) {
  ASSERT_TRUE(upload_surface(*store_, surface_upload_of("P1", "S1", "a"), box_).ok());
  Result<UploadedSurface> again = upload_surface(*store_, surface_upload_of("P1", "S1", "b"), box_);
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  EXPECT_TRUE(again->added.surface_already_stored);
  EXPECT_EQ(stored_structures(), 2);
  EXPECT_EQ(store_->counts()->surfaces, 1);
}

TEST_F(UploadSurfaceTest, MalformedBytesAreInvalidAndStoreNothing) {
  Result<UploadedSurface> up =
      upload_surface(*store_, surface_upload_of("P1", "S1", "junk"), "solid x\nfacet normal oops");
  EXPECT_EQ(up.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(up.status().message(), "junk")) << up.status().message();
  EXPECT_EQ(stored_structures(), 0);
  EXPECT_EQ(store_->counts()->patients, 0);
}

TEST_F(UploadSurfaceTest, AnUnknownFormatIsInvalidAndStoresNothing) {
  SurfaceUpload u = surface_upload_of("P1", "S1", "box");
  u.format = "xyz";
  Result<UploadedSurface> up = upload_surface(*store_, u, box_);
  EXPECT_EQ(up.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(up.status().message(), "unknown mesh format 'xyz'")) << up.status().message();
  EXPECT_EQ(stored_structures(), 0);
}

TEST_F(UploadSurfaceTest, AnOpenSurfaceNeedsRobustModeAndIsStoredWithIt) {
  TriangleMesh open = box({0, 0, 0}, {10, 10, 10});
  open.triangles.pop_back();
  const std::string bytes = stl_of(open);
  SurfaceUpload u = surface_upload_of("P1", "S1", "open");
  Result<UploadedSurface> refused = upload_surface(*store_, u, bytes);
  EXPECT_EQ(refused.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(refused.status().message(), "robust")) << refused.status().message();
  EXPECT_EQ(stored_structures(), 0);
  u.robust = true;
  Result<UploadedSurface> robust = upload_surface(*store_, u, bytes);
  ASSERT_TRUE(robust.ok()) << robust.status().to_string();
  EXPECT_FALSE(robust->defects.closed());
  EXPECT_TRUE(store_->get_structure(robust->added.structure.id)->robust);
}

TEST_F(UploadSurfaceTest, AStudyOfAnotherPatientIsRefusedAndNothingMoves) {
  ASSERT_TRUE(upload_surface(*store_, surface_upload_of("P1", "S1", "a"), box_).ok());
  Result<UploadedSurface> up =
      upload_surface(*store_, surface_upload_of("P2", "S1", "b"), stl_of(box({0, 0, 0}, {1, 2, 3})));
  EXPECT_EQ(up.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(up.status().message(), "another patient")) << up.status().message();
  EXPECT_EQ(stored_structures(), 1);
  EXPECT_EQ(store_->get_study("S1")->patient_id, "P1");
  EXPECT_EQ(store_->get_patient("P2").status().code(), StatusCode::kNotFound);
}

}  // namespace
}  // namespace soiq::server
