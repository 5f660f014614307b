// One DICOM identity, one content: an image series, RT Structure Set or SEG whose UIDs soiq stores
// with other content (other pixels, a slice more or less, another ROI name, an ROI missing) is
// refused as ALREADY_EXISTS naming the UID and what differs, and nothing changes; the same content
// again is a no-op; `replace` replaces, and soiqd logs it.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/integration/service_fixture.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

namespace fs = std::filesystem;

void write_bytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

class DicomIdentityTest : public ServiceTest {
 protected:
  void SetUp() override {
    ServiceTest::SetUp();
    Result<v1::ImportDicomResponse> r = client_->import_dicom({test_data("sts/STS_002/dicom/CT")});
    ASSERT_TRUE(r.ok()) << r.status().to_string();
    ASSERT_EQ(r->series_size(), 1);
    ASSERT_EQ(r->structures_size(), 1);
    series_uid_ = r->series(0).series_uid();
    structure_id_ = r->structures(0).structure().id();
    source_uid_ = r->structures(0).structure().source_uid();
    Result<v1::ServerInfo> info = client_->server_info();
    ASSERT_TRUE(info.ok());
    before_ = *info;
  }

  // A copy of the CT slices in a folder of the test's own.
  std::string copy_of_slices(const std::string& name) {
    const std::string folder = dir_.file(name);
    fs::create_directories(folder);
    for (const auto& e : fs::directory_iterator(test_data("sts/STS_002/dicom/CT/image")))
      fs::copy_file(e.path(), folder + "/" + e.path().filename().string());
    return folder;
  }

  void expect_refused_and_nothing_changed(const Result<v1::ImportDicomResponse>& r, const std::string& words) {
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), StatusCode::kAlreadyExists) << r.status().to_string();
    EXPECT_NE(r.status().message().find(words), std::string::npos) << r.status().message();
    EXPECT_NE(r.status().message().find("--replace"), std::string::npos) << r.status().message();
    Result<v1::ServerInfo> after = client_->server_info();
    ASSERT_TRUE(after.ok());
    EXPECT_EQ(after->series(), before_.series());
    EXPECT_EQ(after->structures(), before_.structures());
    Result<v1::Structure> s = client_->get_structure(structure_id_);
    ASSERT_TRUE(s.ok());
    EXPECT_EQ(s->name(), "GTV_Mass_CT");
  }

  std::string series_uid_, source_uid_;
  int64_t structure_id_ = 0;
  v1::ServerInfo before_;
};

TEST_F(DicomIdentityTest, TheSameContentAgainIsANoOp) {
  Result<v1::ImportDicomResponse> again = client_->import_dicom({test_data("sts/STS_002/dicom/CT")});
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  ASSERT_EQ(again->structures_size(), 1);
  EXPECT_EQ(again->structures(0).structure().id(), structure_id_);
  EXPECT_EQ(server_->log().find("dicom_replaced"), std::string::npos);
}

TEST_F(DicomIdentityTest, ASeriesWithOtherPixelsIsRefusedUnlessReplaced) {
  const std::string folder = copy_of_slices("other_pixels");
  const std::string slice = folder + "/000010.dcm";
  std::string bytes = file_bytes(slice);
  bytes.back() = char(bytes.back() ^ 0x01);  // the last pixel's high byte: Pixel Data ends the file
  write_bytes(slice, bytes);
  expect_refused_and_nothing_changed(client_->import_dicom({folder}),
                                     "series '" + series_uid_ + "' is stored with other content: its voxels differ");
  // Asked for, it is replaced, and the log says so.
  Result<v1::ImportDicomResponse> replaced = client_->import_dicom({folder}, {}, /*replace=*/true);
  ASSERT_TRUE(replaced.ok()) << replaced.status().to_string();
  EXPECT_NE(server_->log().find("event=dicom_replaced series=" + series_uid_), std::string::npos) << server_->log();
  // The original is now the other content.
  expect_refused_and_nothing_changed(client_->import_dicom({test_data("sts/STS_002/dicom/CT/image")}), "voxels differ");
}

TEST_F(DicomIdentityTest, ASeriesWithASliceMissingIsRefused) {
  const std::string folder = copy_of_slices("fewer_slices");
  fs::remove(folder + "/000047.dcm");
  expect_refused_and_nothing_changed(client_->import_dicom({folder}),
                                     "its slices have other SOP Instance UIDs (48 slices stored, 47 sent)");
}

TEST_F(DicomIdentityTest, AStructureSetWithAnotherRoiNameIsRefusedUnlessReplaced) {
  std::string rs = file_bytes(test_data("sts/STS_002/dicom/CT/mask/RS.dcm"));
  size_t at = 0;
  int renamed = 0;
  while ((at = rs.find("GTV_Mass", at)) != std::string::npos) {
    rs[at + 4] = 'Z';  // GTV_Zass: same length, the file stays valid
    ++renamed;
  }
  ASSERT_GT(renamed, 0);
  const std::string path = dir_.file("RS_renamed.dcm");
  write_bytes(path, rs);
  const std::string sop = source_uid_.substr(0, source_uid_.rfind('/'));
  expect_refused_and_nothing_changed(client_->import_dicom({path}), "of DICOM object '" + sop +
                                                                        "' is stored as structure " +
                                                                        std::to_string(structure_id_) +
                                                                        " with another name ('GTV_Mass_CT' stored, "
                                                                        "'GTV_Zass_CT' sent)");
  Result<v1::ImportDicomResponse> replaced = client_->import_dicom({path}, {}, /*replace=*/true);
  ASSERT_TRUE(replaced.ok()) << replaced.status().to_string();
  ASSERT_EQ(replaced->structures_size(), 1);
  EXPECT_EQ(replaced->structures(0).structure().id(), structure_id_);
  EXPECT_EQ(replaced->structures(0).structure().name(), "GTV_Zass_CT");
  EXPECT_NE(server_->log().find("event=dicom_replaced structure=" + std::to_string(structure_id_)), std::string::npos);
}

}  // namespace
}  // namespace soiq::testing
