// soiqd admits conversions, feature computations, image uploads and DICOM imports by their
// estimated peak bytes against one budget (--memory-budget): a request that can never fit is
// refused before it allocates, and parallel requests queue instead of exhausting the machine
// together.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "core/geometry/primitives.h"
#include "tests/integration/service_fixture.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

// An axis-aligned box as OBJ text: a few hundred bytes.
std::string box_obj(double sx, double sy, double sz) {
  std::string text;
  for (int v = 0; v < 8; ++v) {
    text += "v " + std::to_string(v & 1 ? sx : 0) + " " + std::to_string(v & 2 ? sy : 0) + " " +
            std::to_string(v & 4 ? sz : 0) + "\n";
  }
  // Faces as quads, outward; the parser fans them into triangles.
  text += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return text;
}

class MemoryBudgetTest : public ServiceTest {
 protected:
  void start_with(const std::vector<std::string>& args) {
    start(args);
    client_ = std::make_unique<client::Client>(connect());
  }
};

// The bomb: 2.5 x 7500 x 7500 mm at 1 mm is 3.9e8 voxels (under the grid limit) but 5.6e7 row
// lines, each with its own crossings: ~6 GB for a 300-byte file. Refused before any of it exists.
TEST_F(MemoryBudgetTest, ARequestThatCanNeverFitIsRefusedBeforeItAllocates) {
  start_with({"--memory-budget", "1G"});
  v1::UploadSurfaceHeader h = surface_header("P", "S", "slab", "");
  h.set_format("obj");
  Result<v1::UploadSurfaceResponse> up = client_->upload_surface_bytes(h, box_obj(2.5, 7500, 7500));
  ASSERT_TRUE(up.ok()) << up.status().to_string();

  v1::ConvertRequest c;
  c.set_structure_id(up->structure().id());
  c.mutable_grid()->set_spacing_mm(1);
  c.set_encoding(v1::RUNS);
  const auto start = std::chrono::steady_clock::now();
  Result<v1::ConvertSummary> r = client_->convert(c, {});
  const auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted) << r.status().to_string();
  EXPECT_NE(r.status().message().find("memory budget of 1.07 GB"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("structure " + std::to_string(up->structure().id())), std::string::npos);
  EXPECT_EQ(r.status().message().find('\n'), std::string::npos);
  std::printf("refused in %.1f ms: %s\n", ms, r.status().message().c_str());

  v1::FeaturesRequest f;
  f.set_structure_id(up->structure().id());
  f.mutable_grid()->set_spacing_mm(1);
  Result<v1::FeaturesResponse> fr = client_->compute_features(f);
  EXPECT_EQ(fr.status().code(), StatusCode::kResourceExhausted) << fr.status().to_string();

  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->memory_budget_bytes(), int64_t(1) << 30);
  EXPECT_EQ(info->memory_in_use_bytes(), 0);
  EXPECT_LT(server_->peak_rss_bytes(), 1ll << 30);
}

// A 100-byte NRRD announcing 4e8 float voxels: admitted (or not) on its header, before a voxel is
// inflated.
TEST_F(MemoryBudgetTest, AnImageThatCanNeverFitIsRefusedOnItsHeader) {
  start_with({"--memory-budget", "1G"});
  v1::UploadImageHeader h;
  h.mutable_patient()->set_patient_id("P");
  h.mutable_study()->set_study_uid("S");
  h.set_series_uid("1.2.3");
  h.set_modality("CT");
  h.set_format("nrrd");
  const std::string nrrd =
      "NRRD0004\ntype: float\ndimension: 3\nsizes: 1000 1000 400\nendian: little\nencoding: gzip\n\nnot gzip";
  Result<v1::UploadImageResponse> r = client_->upload_image_bytes(h, nrrd);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted) << r.status().to_string();
  EXPECT_NE(r.status().message().find("image '1.2.3' of 1000x1000x400 voxels needs an estimated 4.80 GB"),
            std::string::npos)
      << r.status().message();
  EXPECT_EQ(client_->server_info()->series(), 0);
}

// The STS_002 CT: 48 slices of 161 columns x 143 rows, 4.42 MB as floats. Its import is estimated
// at 12 bytes per voxel (slices, volume, blob) plus one slice at 4 bytes per pixel: 13,353,340 bytes;
// and, for the original files soiqd keeps (--keep-instances), each file twice (as read, and as the
// store binds it) with 16 KiB for its metadata: 2 x 2,328,864 + 48 x 16,384, 18,797,500 bytes in all.
constexpr const char* kStsCt = "sts/STS_002/dicom/CT/image";
constexpr const char* kStsCtUid = "1.3.6.1.4.1.14519.5.2.1.5168.1900.672471348177659964935135533244";
constexpr int64_t kStsCtVoxelsEstimate = int64_t(161) * 143 * 48 * 12 + 161 * 143 * 4;
int64_t sts_ct_files_estimate() {
  int64_t bytes = 0;
  for (const auto& f : std::filesystem::directory_iterator(test_data(kStsCt)))
    bytes += 2 * int64_t(f.file_size()) + 16384;
  return bytes;
}

TEST_F(MemoryBudgetTest, ADicomSeriesThatCanNeverFitIsRefusedBeforeAnythingIsStored) {
  start_with({"--memory-budget", "4M"});  // under the CT's 4.42 MB of floats alone
  Result<v1::ImportDicomResponse> r = client_->import_dicom({test_data(kStsCt)});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted) << r.status().to_string();
  const std::string& message = r.status().message();
  EXPECT_NE(message.find("importing series " + std::string(kStsCtUid) + " (161x143x48) needs an estimated 18.8 MB"),
            std::string::npos)
      << message;
  // A quarter of soiqd's budget is its decoded-object caches'; the message says what is left for work.
  EXPECT_NE(message.find("more than the 3.15 MB that soiqd's memory budget of 4.19 MB leaves beside 1.05 MB of "
                         "decoded-object caches (soiqd --memory-budget): raise the budget"),
            std::string::npos)
      << message;
  std::printf("refused: %s\n", message.c_str());

  Result<v1::ServerInfo> info = client_->server_info();  // still serving
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->patients(), 0);
  EXPECT_EQ(info->studies(), 0);
  EXPECT_EQ(info->series(), 0);
  EXPECT_EQ(info->memory_in_use_bytes(), 0);
  EXPECT_EQ(info->memory_peak_bytes(), 0);  // refused before reserving, so before decoding
}

TEST_F(MemoryBudgetTest, ADicomImportReservesItsEstimateBeforeDecoding) {
  start_with({"--memory-budget", "1G"});
  Result<v1::ImportDicomResponse> r = client_->import_dicom({test_data(kStsCt)});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  ASSERT_EQ(r->series_size(), 1);
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->series(), 1);
  const int64_t estimate = kStsCtVoxelsEstimate + sts_ct_files_estimate();
  EXPECT_GE(info->memory_peak_bytes(), estimate);
  EXPECT_EQ(info->memory_in_use_bytes(), 0);  // given back once stored
  std::printf("memory_peak_bytes %lld, estimate %lld\n", static_cast<long long>(info->memory_peak_bytes()),
              static_cast<long long>(estimate));
}

// Four NIfTI conversions of a 3e8-voxel grid (each ~0.65 GB at its peak, ~1 GB estimated) sent at
// once to four workers: the 1.6 GB budget (1.2 GB for work beside a quarter for the decoded-object
// caches) runs them one at a time, so soiqd's peak stays under it.
TEST_F(MemoryBudgetTest, ParallelConversionsQueueWithinTheBudget) {
  const int64_t budget = int64_t(1600) << 20;
  const int64_t for_work = budget - budget / 4;
  start_with({"--memory-budget", std::to_string(budget), "--workers", "4"});
  Result<v1::UploadSurfaceResponse> up = upload(uv_sphere({0, 0, 0}, 100, 64, 128), "P", "S", "ball");
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  std::vector<std::thread> clients;
  std::vector<Status> results(4);
  for (int n = 0; n < 4; ++n) {
    clients.emplace_back([&, n] {
      client::Client own = connect();
      v1::ConvertRequest c;
      c.set_structure_id(up->structure().id());
      c.mutable_grid()->set_spacing_mm(0.3);  // 673^3 voxels
      int64_t bytes = 0;
      client::ConvertHandlers handlers;
      handlers.on_nifti = [&](std::string_view chunk) {
        bytes += int64_t(chunk.size());
        return true;
      };
      Result<v1::ConvertSummary> r = own.convert(c, handlers);
      results[size_t(n)] = r.ok() ? (bytes > 0 ? ok_status() : internal_error("no NIfTI bytes")) : r.status();
    });
  }
  for (auto& t : clients) t.join();
  for (const Status& s : results) EXPECT_TRUE(s.ok()) << s.to_string();
  const long long peak = server_->peak_rss_bytes();
  EXPECT_GT(peak, 0);
  EXPECT_LT(peak, budget) << "soiqd's VmHWM " << peak << " bytes exceeds its budget of " << budget;
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_LE(info->memory_peak_bytes(), for_work);
  EXPECT_EQ(info->memory_in_use_bytes(), 0);
}

}  // namespace
}  // namespace soiq::testing
