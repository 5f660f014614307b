// The Render RPC through a real soiqd: which slice and image it draws, checked against the voxels
// the Convert RPC gives for the same structure on the same grid (an independent count per slice);
// the window the DICOM gives; a montage of exactly the slices holding the structure; a mesh without
// images drawn as its mask alone; and each bad request refused with its field.
#include <cairo.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/primitives.h"
#include "tests/integration/service_fixture.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

namespace fs = std::filesystem;

// Voxels inside per k of the structure on `series_uid`'s grid, from the Convert RPC's runs.
std::map<int64_t, int64_t> voxels_per_k(const client::Client& c, int64_t id, const std::string& series_uid) {
  v1::ConvertRequest request;
  request.set_structure_id(id);
  request.mutable_grid()->set_series_uid(series_uid);
  request.set_encoding(v1::RUNS);
  std::map<int64_t, int64_t> per_k;
  client::ConvertHandlers handlers;
  handlers.on_runs = [&](const v1::RunBatch& b) {
    for (int r = 0; r < b.k_size(); ++r) per_k[b.k(r)] += b.end(r) - b.begin(r);
    return true;
  };
  Result<v1::ConvertSummary> s = c.convert(request, handlers);
  EXPECT_TRUE(s.ok()) << s.status().to_string();
  return per_k;
}

// Width and height of a PNG file, read back by cairo (0, 0 when it is not one).
std::pair<int, int> png_size(const std::string& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  std::pair<int, int> size{0, 0};
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS)
    size = {cairo_image_surface_get_width(s), cairo_image_surface_get_height(s)};
  cairo_surface_destroy(s);
  return size;
}

std::string file_head(const std::string& path, size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string head(n, '\0');
  in.read(head.data(), std::streamsize(n));
  head.resize(size_t(in.gcount()));
  return head;
}

class RenderTest : public ServiceTest {
 protected:
  // STS_002's CT and its GTV: the structure id and the CT's series uid.
  std::pair<int64_t, std::string> import_sts_ct(const std::string& folder) {
    Result<v1::ImportDicomResponse> r = client_->import_dicom({folder});
    EXPECT_TRUE(r.ok()) << r.status().to_string();
    if (!r.ok()) return {0, ""};
    for (const v1::ImportedStructure& s : r->structures())
      for (const v1::Series& se : r->series())
        if (se.modality() == "CT" && s.referenced_series_uid() == se.series_uid())
          return {s.structure().id(), se.series_uid()};
    ADD_FAILURE() << "no structure on the CT";
    return {0, ""};
  }
};

TEST_F(RenderTest, DrawsTheLargestAndTheCentroidSliceOfTheVoxelsConvertGives) {
  const auto [id, ct] = import_sts_ct(test_data("sts/STS_002/dicom/CT"));
  ASSERT_GT(id, 0);
  const std::map<int64_t, int64_t> per_k = voxels_per_k(*client_, id, ct);
  ASSERT_FALSE(per_k.empty());
  int64_t largest = per_k.begin()->first, total = 0;
  double weighted = 0;
  for (const auto& [k, n] : per_k) {
    if (n > per_k.at(largest)) largest = k;
    total += n;
    weighted += double(k) * double(n);
  }
  v1::RenderRequest request;
  request.set_structure_id(id);
  const std::string out = dir_.file("largest.png");
  Result<v1::RenderInfo> info = client_->render(request, out);
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->series_uid(), ct);  // the series it was imported on, by default
  EXPECT_EQ(info->plane(), v1::AXIAL);
  ASSERT_EQ(info->slices_size(), 1);
  EXPECT_EQ(info->slices(0), largest);
  EXPECT_EQ(info->media_type(), "image/png");
  EXPECT_EQ(png_size(out), std::make_pair(info->width(), info->height()));
  EXPECT_EQ(int64_t(fs::file_size(out)), info->size_bytes());
  EXPECT_GT(info->window_width(), 0);  // this CT has no window of its own: the robust default

  request.set_through(v1::CENTROID);
  info = client_->render(request, dir_.file("centroid.png"));
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->slices(0), std::llround(weighted / double(total)));
}

TEST_F(RenderTest, AMontageHoldsExactlyTheSlicesWithVoxelsAndEachFormatIsItsFile) {
  const auto [id, ct] = import_sts_ct(test_data("sts/STS_002/dicom/CT"));
  ASSERT_GT(id, 0);
  const std::map<int64_t, int64_t> per_k = voxels_per_k(*client_, id, ct);
  std::vector<int64_t> with_voxels;
  for (const auto& [k, n] : per_k)
    if (n > 0) with_voxels.push_back(k);
  v1::RenderRequest request;
  request.set_structure_id(id);
  request.set_montage(true);
  request.set_format(v1::SVG);
  Result<v1::RenderInfo> info = client_->render(request, dir_.file("montage.svg"));
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(std::vector<int64_t>(info->slices().begin(), info->slices().end()), with_voxels);
  EXPECT_EQ(info->media_type(), "image/svg+xml");
  EXPECT_NE(file_head(dir_.file("montage.svg"), 200).find("<svg"), std::string::npos);

  request.set_montage(false);
  request.set_format(v1::JPEG);
  request.set_jpeg_quality(70);
  request.set_plane(v1::CORONAL);
  info = client_->render(request, dir_.file("coronal.jpg"));
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->plane(), v1::CORONAL);
  EXPECT_EQ(file_head(dir_.file("coronal.jpg"), 3), std::string("\xFF\xD8\xFF"));
}

TEST_F(RenderTest, TheWindowComesFromTheDicomWhenItHasOne) {
  // STS_002's CT with Window Center/Width written into every slice.
  const std::string folder = dir_.file("ct_window");
  fs::create_directories(folder);
  for (const auto& entry : fs::recursive_directory_iterator(test_data("sts/STS_002/dicom/CT"))) {
    if (!entry.is_regular_file()) continue;
    DcmFileFormat file;
    if (file.loadFile(entry.path().c_str()).bad()) continue;
    ASSERT_TRUE(file.getDataset()->putAndInsertString(DCM_WindowCenter, "40\\300").good());
    ASSERT_TRUE(file.getDataset()->putAndInsertString(DCM_WindowWidth, "400\\1500").good());
    const std::string out = folder + "/" + std::to_string(files_++) + ".dcm";
    ASSERT_TRUE(file.saveFile(out.c_str(), EXS_LittleEndianExplicit).good());
  }
  const auto [id, ct] = import_sts_ct(folder);
  ASSERT_GT(id, 0);
  v1::RenderRequest request;
  request.set_structure_id(id);
  Result<v1::RenderInfo> info = client_->render(request, dir_.file("window.png"));
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->window_center(), 40);  // the first of the DICOM's windows
  EXPECT_EQ(info->window_width(), 400);
  request.set_window_center(-600);
  request.set_window_width(1600);
  info = client_->render(request, dir_.file("lung.png"));
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->window_center(), -600);  // asked for wins
  EXPECT_EQ(info->window_width(), 1600);
}

TEST_F(RenderTest, APictureThatCanNeverFitTheMemoryBudgetIsRefusedBeforeItIsDrawn) {
  start({"--memory-budget", "128M"});
  client_ = std::make_unique<client::Client>(connect());
  const auto [id, ct] = import_sts_ct(test_data("sts/STS_002/dicom/CT"));
  ASSERT_GT(id, 0);
  v1::RenderRequest request;
  request.set_structure_id(id);
  request.set_montage(true);
  request.set_width(8192);  // 16 tiles of ~2000 pixels: ~0.4 GB of surface and copies
  Result<v1::RenderInfo> info = client_->render(request, dir_.file("huge.png"));
  ASSERT_FALSE(info.ok());
  EXPECT_EQ(info.status().code(), StatusCode::kResourceExhausted) << info.status().to_string();
  EXPECT_FALSE(fs::exists(dir_.file("huge.png")));
  request.set_width(1024);  // the same montage, smaller, fits
  info = client_->render(request, dir_.file("small.png"));
  ASSERT_TRUE(info.ok()) << info.status().to_string();
}

TEST_F(RenderTest, AMeshWithoutImagesIsDrawnAsItsMaskAlone) {
  Result<v1::UploadSurfaceResponse> up = upload(uv_sphere({0, 0, 0}, 10, 12, 24), "P1", "1.2.3", "ball");
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  v1::RenderRequest request;
  request.set_structure_id(up->structure().id());
  Result<v1::RenderInfo> info = client_->render(request, dir_.file("ball.png"));
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->series_uid(), "");
  EXPECT_GT(png_size(dir_.file("ball.png")).first, 0);
}

TEST_F(RenderTest, BadRequestsAreRefusedWithTheirFieldAndNothingIsWritten) {
  const auto [id, ct] = import_sts_ct(test_data("sts/STS_002/dicom/CT"));
  ASSERT_GT(id, 0);
  struct Case {
    const char* what;
    std::function<void(v1::RenderRequest&)> set;
    StatusCode code;
    std::string field, text;
  };
  const std::vector<Case> cases = {
      {"unknown id", [](v1::RenderRequest& r) { r.set_structure_id(999999); }, StatusCode::kNotFound, "", "999999"},
      {"slice past the end", [](v1::RenderRequest& r) { r.set_slice(100000); }, StatusCode::kInvalidArgument, "slice",
       "outside 0.."},
      {"window without width", [](v1::RenderRequest& r) { r.set_window_center(40); }, StatusCode::kInvalidArgument,
       "window_width", "together"},
      {"window width 0",
       [](v1::RenderRequest& r) {
         r.set_window_center(40);
         r.set_window_width(0);
       },
       StatusCode::kInvalidArgument, "window_width", "> 0"},
      {"width too large", [](v1::RenderRequest& r) { r.set_width(100000); }, StatusCode::kInvalidArgument, "width",
       "outside 0..8192"},
      {"slice and montage",
       [](v1::RenderRequest& r) {
         r.set_slice(1);
         r.set_montage(true);
       },
       StatusCode::kInvalidArgument, "slice", "not both"},
      {"unknown image", [](v1::RenderRequest& r) { r.set_image("US"); }, StatusCode::kNotFound, "", "US"},
      {"bad plane", [](v1::RenderRequest& r) { r.set_plane(v1::Plane(42)); }, StatusCode::kInvalidArgument, "plane",
       ""},
  };
  for (const Case& c : cases) {
    v1::RenderRequest request;
    request.set_structure_id(id);
    c.set(request);
    const std::string out = dir_.file(std::string("refused_") + std::to_string(files_++) + ".png");
    Result<v1::RenderInfo> info = client_->render(request, out);
    ASSERT_FALSE(info.ok()) << c.what;
    EXPECT_EQ(info.status().code(), c.code) << c.what << ": " << info.status().to_string();
    if (!c.field.empty()) {
      EXPECT_EQ(info.status().field(), c.field) << c.what << ": " << info.status().to_string();
    }
    EXPECT_NE(info.status().message().find(c.text), std::string::npos) << c.what << ": " << info.status().message();
    EXPECT_FALSE(fs::exists(out)) << c.what;
  }
}

}  // namespace
}  // namespace soiq::testing
