// ImportDicom through a real soiqd: exported SEGs coming back, and the study identity they carry.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/integration/service_fixture.h"

namespace soiq::testing {
namespace {

std::string sts002(const std::string& relative) {
  return std::string(SOIQ_TEST_DATA_DIR) + "/sts/STS_002/dicom/" + relative;
}

const v1::ImportedStructure* only_structure(const v1::ImportDicomResponse& r) {
  return r.structures_size() == 1 ? &r.structures(0) : nullptr;
}

TEST_F(ServiceTest, OurOwnSegImportedBackTwiceIsRecognisedAndAddsNoStructure) {
  Result<v1::ImportDicomResponse> ct = client_->import_dicom({sts002("CT")});
  ASSERT_TRUE(ct.ok()) << ct.status().to_string();
  const v1::ImportedStructure* gtv = only_structure(*ct);
  ASSERT_NE(gtv, nullptr);
  v1::ExportSegRequest e;
  e.add_structure_ids(gtv->structure().id());
  const std::string seg = dir_.file("gtv_seg.dcm");
  Result<v1::SegInfo> exported = client_->export_seg(e, seg);
  ASSERT_TRUE(exported.ok()) << exported.status().to_string();

  for (int i = 0; i < 2; ++i) {
    Result<v1::ImportDicomResponse> back = client_->import_dicom({seg});
    ASSERT_TRUE(back.ok()) << back.status().to_string();
    for (const v1::ImportProblem& p : back->problems()) ADD_FAILURE() << p.path() << ": " << p.message();
    const v1::ImportedStructure* same = only_structure(*back);
    ASSERT_NE(same, nullptr) << back->structures_size();
    EXPECT_EQ(same->structure().id(), gtv->structure().id()) << "import " << i + 1;
    EXPECT_EQ(same->structure().source_uid(), gtv->structure().source_uid());
    EXPECT_TRUE(same->replaced());
    EXPECT_EQ(same->voxel_count(), gtv->voxel_count());
    Result<v1::ServerInfo> info = client_->server_info();
    ASSERT_TRUE(info.ok());
    EXPECT_EQ(info->structures(), 1) << "import " << i + 1;
  }
  // The structure set itself still updates the same structure.
  Result<v1::ImportDicomResponse> rt = client_->import_dicom({sts002("CT")});
  ASSERT_TRUE(rt.ok());
  EXPECT_EQ(client_->server_info()->structures(), 1);
}

std::string text_of(DcmDataset& ds, const DcmTagKey& tag) {
  OFString v;
  return ds.findAndGetOFString(tag, v).good() ? std::string(v.c_str()) : "<absent>";
}

// STS_002's CT (images and structure set) copied to `to`, its Study ID shortened in place (same
// length, space padded) to one DICOM SH can hold: the shipped "IBSI_1_STS_002_CT" has 17
// characters, one over SH's 16, so no SEG could carry it.
void copy_sts002_ct_with_a_short_study_id(const std::filesystem::path& to) {
  const std::string from = "IBSI_1_STS_002_CT ", short_id = "STS_002_CT        ";
  for (const auto& e : std::filesystem::recursive_directory_iterator(sts002("CT"))) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::string bytes(std::istreambuf_iterator<char>(in), {});
    for (size_t at = bytes.find(from); at != std::string::npos; at = bytes.find(from, at))
      bytes.replace(at, from.size(), short_id);
    std::ofstream(to / (e.path().parent_path().filename().string() + "_" + e.path().filename().string()),
                  std::ios::binary)
        << bytes;
  }
}

TEST_F(ServiceTest, ExportedSegCarriesTheStudyTimeIdAndAccessionNumberOfItsStudy) {
  const std::filesystem::path copy = dir_.file("sts002_ct");
  std::filesystem::create_directories(copy);
  copy_sts002_ct_with_a_short_study_id(copy);
  Result<v1::ImportDicomResponse> ct = client_->import_dicom({copy.string()});
  ASSERT_TRUE(ct.ok()) << ct.status().to_string();
  const v1::ImportedStructure* gtv = only_structure(*ct);
  ASSERT_NE(gtv, nullptr);
  v1::ExportSegRequest e;
  e.add_structure_ids(gtv->structure().id());
  const std::string seg = dir_.file("gtv_seg.dcm");
  ASSERT_TRUE(client_->export_seg(e, seg).ok());

  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(seg.c_str()).good());
  DcmDataset& ds = *file.getDataset();
  // The values of the CT files (dcmdump tests/data/sts/STS_002/dicom/CT/image/*).
  EXPECT_EQ(text_of(ds, DCM_StudyTime), "145427");
  EXPECT_EQ(text_of(ds, DCM_AccessionNumber), "3912173256621705");
  EXPECT_EQ(text_of(ds, DCM_StudyID), "STS_002_CT");
}

}  // namespace
}  // namespace soiq::testing
