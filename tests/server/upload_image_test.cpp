// The UploadImage engine on its own, without gRPC: a small NIfTI image stored as a series of a real
// SQLite store with its geometry, replaced in place by the same uid; malformed bytes, an image over
// the budget or the voxel limit and a series of another patient refused with nothing stored and
// nothing left reserved; a caller gone while it waits for the budget stops it.
#include "server/app/upload_image.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "core/io/write_image.h"
#include "tests/db/temp_store.h"

namespace soiq::server {
namespace {

using db::testing::contains;
using db::testing::TempDir;

ImageUpload upload_of(const std::string& patient, const std::string& study, const std::string& series) {
  ImageUpload u;
  u.patient.patient_id = patient;
  u.study.study_uid = study;
  u.study.patient_id = patient;
  u.series_uid = series;
  u.modality = "PT";
  u.format = "nii.gz";
  return u;
}

class UploadImageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    image_.geometry.dims = {4, 3, 2};
    image_.geometry.spacing_mm = {1, 1.5, 2};
    image_.geometry.origin_mm = {-5, 10, 20};
    for (int i = 0; i < 24; ++i) image_.voxels.push_back(float(i));
    const std::string path = tmp_.file("image.nii.gz");
    ASSERT_TRUE(write_image(image_, path).ok());
    std::ifstream in(path, std::ios::binary);
    bytes_.assign(std::istreambuf_iterator<char>(in), {});
    ASSERT_FALSE(bytes_.empty());
  }

  Result<UploadedImage> upload(const ImageUpload& u, const std::string& bytes) {
    return upload_image(*store_, budget_, int64_t(1) << 26, u, bytes, never_stop_);
  }
  int64_t stored_series() {
    Result<db::Counts> c = store_->counts();
    EXPECT_TRUE(c.ok()) << c.status().to_string();
    return c.ok() ? c->series : -1;
  }

  TempDir tmp_;
  std::unique_ptr<db::SqliteStore> store_ = db::testing::open_store(tmp_.file("soiq.db"));
  MemoryBudget budget_{int64_t(1) << 30};
  Image image_;
  std::string bytes_;
  std::function<Status()> never_stop_ = [] { return ok_status(); };
};

TEST_F(UploadImageTest, AnImageIsStoredAsASeriesWithItsGeometry) {
  Result<UploadedImage> up = upload(upload_of("P1", "S1", "1.2.3"), bytes_);
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  EXPECT_FALSE(up->replaced);
  EXPECT_EQ(up->series.study_uid, "S1");
  EXPECT_FALSE(up->series.sha256.empty());
  Result<db::SeriesRecord> stored = store_->get_series("1.2.3");
  ASSERT_TRUE(stored.ok()) << stored.status().to_string();
  EXPECT_EQ(stored->modality, "PT");
  EXPECT_EQ(stored->sha256, up->series.sha256);
  EXPECT_EQ(stored->geometry.dims, image_.geometry.dims);
  for (int a = 0; a < 3; ++a) {
    // NIfTI stores spacing and origin as float32: these values are exact in it.
    EXPECT_EQ(stored->geometry.spacing_mm[a], image_.geometry.spacing_mm[a]);
    EXPECT_EQ(stored->geometry.origin_mm[a], image_.geometry.origin_mm[a]);
  }
  EXPECT_EQ(budget_.in_use(), 0);
  EXPECT_GT(budget_.peak(), 0);
}

TEST_F(UploadImageTest, TheSameUidAgainReplacesTheSeries) {
  ASSERT_TRUE(upload(upload_of("P1", "S1", "1.2.3"), bytes_).ok());
  Result<UploadedImage> again = upload(upload_of("P1", "S1", "1.2.3"), bytes_);
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  EXPECT_TRUE(again->replaced);
  EXPECT_EQ(stored_series(), 1);
}

TEST_F(UploadImageTest, MalformedBytesAreInvalidAndStoreNothing) {
  Result<UploadedImage> up = upload(upload_of("P1", "S1", "1.2.3"), "this is not a NIfTI file at all");
  EXPECT_EQ(up.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(stored_series(), 0);
  EXPECT_EQ(store_->counts()->patients, 0);
  EXPECT_EQ(budget_.in_use(), 0);
}

TEST_F(UploadImageTest, AnImageThatCanNeverFitTheBudgetIsRefusedBeforeDecoding) {
  MemoryBudget tiny(64);
  Result<UploadedImage> up =
      upload_image(*store_, tiny, int64_t(1) << 26, upload_of("P1", "S1", "1.2.3"), bytes_, never_stop_);
  EXPECT_EQ(up.status().code(), StatusCode::kResourceExhausted);
  EXPECT_TRUE(contains(up.status().message(), "image '1.2.3' of 4x3x2 voxels")) << up.status().message();
  EXPECT_TRUE(contains(up.status().message(), "--memory-budget")) << up.status().message();
  EXPECT_EQ(tiny.peak(), 0);
  EXPECT_EQ(stored_series(), 0);
}

TEST_F(UploadImageTest, AGridOverTheVoxelLimitIsRefused) {
  Result<UploadedImage> up = upload_image(*store_, budget_, 23, upload_of("P1", "S1", "1.2.3"), bytes_, never_stop_);
  EXPECT_EQ(up.status().code(), StatusCode::kResourceExhausted);
  EXPECT_EQ(budget_.peak(), 0);
  EXPECT_EQ(stored_series(), 0);
}

TEST_F(UploadImageTest, ACallerGoneWhileWaitingForTheBudgetStopsTheUpload) {
  MemoryBudget small(1000);
  Result<MemoryBudget::Reservation> other = small.reserve(990, "another upload");
  ASSERT_TRUE(other.ok());
  Result<UploadedImage> up = upload_image(*store_, small, int64_t(1) << 26, upload_of("P1", "S1", "1.2.3"), bytes_, [] {
    return Status(StatusCode::kCancelled, "the request was cancelled by the client");
  });
  EXPECT_EQ(up.status().code(), StatusCode::kCancelled);
  EXPECT_EQ(small.in_use(), 990);
  EXPECT_EQ(stored_series(), 0);
}

TEST_F(UploadImageTest, ASeriesOfAnotherPatientIsRefusedAndStaysWhereItWas) {
  ASSERT_TRUE(upload(upload_of("P1", "S1", "1.2.3"), bytes_).ok());
  Result<UploadedImage> up = upload(upload_of("P2", "S2", "1.2.3"), bytes_);
  EXPECT_EQ(up.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(up.status().message(), "another patient")) << up.status().message();
  EXPECT_EQ(store_->get_series("1.2.3")->study_uid, "S1");
  EXPECT_EQ(store_->get_study("S2").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(budget_.in_use(), 0);
}

}  // namespace
}  // namespace soiq::server
