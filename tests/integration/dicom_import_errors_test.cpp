// ImportDicom through a real soiqd: problems that do not stop an import, and failed imports (a
// corrupt file, a header that disagrees with its pixels, an upload over the limit) that store
// nothing.

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "tests/integration/service_fixture.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

TEST_F(ServiceTest, ImportOfMixedFilesReportsProblemsWithoutFailing) {
  Result<v1::ImportDicomResponse> r = client_->import_dicom({test_data("dicom")});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_GT(r->series_size(), 0);
  EXPECT_GT(r->problems_size(), 0);  // the CR series, README files, the DICOMDIR variants' failures...
  for (const v1::ImportProblem& p : r->problems()) {
    // Problems name files as sent (relative to the folder), never the server's temporary folder.
    EXPECT_EQ(p.message().find("soiqd-import-"), std::string::npos) << p.message();
    EXPECT_EQ(p.path().find("soiqd-import-"), std::string::npos) << p.path();
  }
}

TEST_F(ServiceTest, ImportOfACorruptFileAloneIsInvalidAndStoresNothing) {
  const std::string path = dir_.file("broken.dcm");
  {
    std::ofstream out(path, std::ios::binary);
    out << std::string(128, '\0') << "DICM" << std::string(40, '\xff') << "garbage";
  }
  Result<v1::ServerInfo> before = client_->server_info();
  ASSERT_TRUE(before.ok());
  Result<v1::ImportDicomResponse> r = client_->import_dicom({path});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  EXPECT_NE(r.status().message().find("broken.dcm"), std::string::npos) << r.status().message();
  Result<v1::ServerInfo> after = client_->server_info();
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(after->patients(), before->patients());
  EXPECT_EQ(after->series(), before->series());
  EXPECT_EQ(after->structures(), before->structures());
}

TEST_F(ServiceTest, ImportOfACtWhoseRowsDisagreeWithItsPixelsIsInvalidNamingFileAndTagAndStoresNothing) {
  // CT_small is 128 x 128 x 16 bit; its header made to say 64 rows. Patched in place (the tag,
  // VR US, length 2, value 128 little-endian) so the file is otherwise the real one.
  std::string bytes;
  {
    std::ifstream in(test_data("dicom/CT_small.dcm"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string rows("\x28\x00\x10\x00US\x02\x00\x80\x00", 10);
  const size_t at = bytes.find(rows);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 8] = 64;
  const std::string path = dir_.file("hostile_ct.dcm");
  std::ofstream(path, std::ios::binary) << bytes;
  ASSERT_TRUE(client_->import_dicom({test_data("sts/STS_002/dicom/CT/image")}).ok());
  Result<v1::ServerInfo> before = client_->server_info();
  ASSERT_TRUE(before.ok());

  Result<v1::ImportDicomResponse> r = client_->import_dicom({path});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  const std::string& m = r.status().message();
  EXPECT_NE(m.find("'hostile_ct.dcm': Pixel Data (7FE0,0010) has 32768 bytes but Rows (0028,0010)"), std::string::npos)
      << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  EXPECT_EQ(m.find("soiqd-import-"), std::string::npos) << m;  // the name as sent, not the server's folder
  // Still serving, and nothing of the file was kept.
  Result<v1::ServerInfo> after = client_->server_info();
  ASSERT_TRUE(after.ok()) << after.status().to_string();
  EXPECT_EQ(after->patients(), before->patients());
  EXPECT_EQ(after->studies(), before->studies());
  EXPECT_EQ(after->series(), before->series());
  EXPECT_EQ(after->structures(), before->structures());
}

TEST_F(ServiceTest, ImportOverTheUploadLimitIsResourceExhausted) {
  start({"--max-upload-bytes", "100000"});
  client_ = std::make_unique<client::Client>(connect());
  Result<v1::ImportDicomResponse> r = client_->import_dicom({test_data("sts/STS_002/dicom")});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted) << r.status().to_string();
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->series(), 0);
}

}  // namespace
}  // namespace soiq::testing
