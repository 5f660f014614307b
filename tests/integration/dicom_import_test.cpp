// ImportDicom through a real soiqd: the STS_002 CT and PET with their RT Structure Sets, features on
// the patient's own grids and images, problems that do not stop an import, and failed imports (a
// corrupt file, a header that disagrees with its pixels) that store nothing.
// Exported SEGs coming back, and the study identity they carry.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "core/io/read_image.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/sts_query.h"

namespace soiq::testing {
namespace {

std::string data(const std::string& relative) { return std::string(SOIQ_TEST_DATA_DIR) + "/" + relative; }

const v1::Series* series_of_modality(const v1::ImportDicomResponse& r, const std::string& modality) {
  for (const v1::Series& s : r.series())
    if (s.modality() == modality) return &s;
  return nullptr;
}

TEST_F(ServiceTest, ImportsSts002WithItsSeriesAndStructures) {
  Result<v1::ImportDicomResponse> r = client_->import_dicom({data("sts/STS_002/dicom")});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  for (const v1::ImportProblem& p : r->problems()) ADD_FAILURE() << p.path() << ": " << p.message();
  ASSERT_EQ(r->patients_size(), 1);
  EXPECT_EQ(r->patients(0).patient_id(), "STS_002");
  EXPECT_EQ(r->files_received(), 98);
  ASSERT_EQ(r->series_size(), 2);
  const v1::Series* ct = series_of_modality(*r, "CT");
  const v1::Series* pt = series_of_modality(*r, "PT");
  ASSERT_TRUE(ct && pt);
  ASSERT_EQ(r->structures_size(), 2);  // one GTV per structure set, on CT and on PET
  for (const v1::ImportedStructure& s : r->structures()) {
    EXPECT_EQ(s.structure().name().rfind("GTV_Mass", 0), 0u) << s.structure().name();
    EXPECT_EQ(s.structure().patient_id(), "STS_002");
    EXPECT_GT(s.voxel_count(), 0);
  }
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->series(), 2);
  EXPECT_EQ(info->structures(), 2);
}

TEST_F(ServiceTest, ImportKeepsDicomReferencesAndAReimportUpdatesInPlace) {
  Result<v1::ImportDicomResponse> first = client_->import_dicom({data("sts/STS_002/dicom")});
  ASSERT_TRUE(first.ok()) << first.status().to_string();
  const v1::Series* ct = series_of_modality(*first, "CT");
  ASSERT_NE(ct, nullptr);
  // What a DICOM SEG on this series must reference.
  EXPECT_FALSE(ct->frame_of_reference_uid().empty());
  EXPECT_EQ(ct->sop_class_uid(), "1.2.840.10008.5.1.4.1.1.2");  // CT Image Storage
  EXPECT_EQ(ct->slice_instance_count(), ct->geometry().dims(2));
  std::map<std::string, int64_t> ids;  // by source uid
  for (const v1::ImportedStructure& s : first->structures()) {
    EXPECT_FALSE(s.replaced());
    EXPECT_EQ(s.structure().source_series_uid(), s.referenced_series_uid());
    ASSERT_NE(s.structure().source_uid().find('/'), std::string::npos) << s.structure().source_uid();
    ids[s.structure().source_uid()] = s.structure().id();
  }
  ASSERT_EQ(ids.size(), 2u);

  Result<v1::ImportDicomResponse> again = client_->import_dicom({data("sts/STS_002/dicom")});
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  ASSERT_EQ(again->structures_size(), 2);
  for (const v1::ImportedStructure& s : again->structures()) {
    EXPECT_TRUE(s.replaced()) << s.structure().name();
    EXPECT_EQ(s.structure().id(), ids[s.structure().source_uid()]);
  }
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->structures(), 2);
  EXPECT_EQ(info->series(), 2);
}

TEST_F(ServiceTest, ImportedCtStructureHasTheMaskVolumeOnCtAndPetUptake) {
  Result<v1::ImportDicomResponse> r = client_->import_dicom({data("sts/STS_002/dicom")});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const v1::Series* ct = series_of_modality(*r, "CT");
  ASSERT_NE(ct, nullptr);
  const v1::ImportedStructure* on_ct = nullptr;
  for (const v1::ImportedStructure& s : r->structures())
    if (s.referenced_series_uid() == ct->series_uid()) on_ct = &s;
  ASSERT_NE(on_ct, nullptr);

  Result<Image> mask = read_image(data("sts/STS_002/CT_mask.nii.gz"));
  ASSERT_TRUE(mask.ok()) << mask.status().to_string();
  int64_t inside = 0;
  for (float v : mask->voxels) inside += v != 0;
  ASSERT_GT(inside, 0);
  EXPECT_EQ(on_ct->voxel_count(), inside);

  v1::FeaturesRequest f;
  f.set_structure_id(on_ct->structure().id());
  f.mutable_grid()->set_series_modality("CT");
  f.add_features("voxel_volume_mm3");
  f.add_features("mean");
  f.add_regions("inside");
  f.add_images("PT");
  Result<v1::FeaturesResponse> features = client_->compute_features(f);
  ASSERT_TRUE(features.ok()) << features.status().to_string();
  const v1::ImageGeometry& g = features->geometry();
  const double voxel_mm3 = g.spacing(0) * g.spacing(1) * g.spacing(2);
  bool volume_seen = false, mean_seen = false;
  for (const v1::FeatureValue& v : features->features()) {
    if (v.name() == "voxel_volume_mm3") {
      volume_seen = true;
      // The marching-cubes surface re-converted on its own grid gives back exactly the mask's voxels.
      EXPECT_EQ(v.value(0), double(inside) * voxel_mm3);
    }
    if (v.name() == "mean" && v.image() == "PT") {
      mean_seen = true;
      EXPECT_GT(v.value(0), 0.0);  // SUV inside a PET-avid sarcoma
    }
  }
  EXPECT_TRUE(volume_seen && mean_seen);

  Result<QueryResult> s = run_query(*client_, gtv_mean_pet_query());
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  for (const v1::QueryRow& row : s->rows) EXPECT_EQ(row.patient().patient_id(), "STS_002");
  EXPECT_GE(s->rows.size(), 1u);
  EXPECT_EQ(s->summary.failed(), 0);
}

TEST_F(ServiceTest, ImportOfMixedFilesReportsProblemsWithoutFailing) {
  Result<v1::ImportDicomResponse> r = client_->import_dicom({data("dicom")});
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
    std::ifstream in(data("dicom/CT_small.dcm"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string rows("\x28\x00\x10\x00US\x02\x00\x80\x00", 10);
  const size_t at = bytes.find(rows);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 8] = 64;
  const std::string path = dir_.file("hostile_ct.dcm");
  std::ofstream(path, std::ios::binary) << bytes;
  ASSERT_TRUE(client_->import_dicom({data("sts/STS_002/dicom/CT/image")}).ok());
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
  Result<v1::ImportDicomResponse> r = client_->import_dicom({data("sts/STS_002/dicom")});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted) << r.status().to_string();
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->series(), 0);
}

}  // namespace
}  // namespace soiq::testing

namespace soiq::testing {
namespace {

std::string sts(const std::string& relative) {
  return std::string(SOIQ_TEST_DATA_DIR) + "/sts/STS_002/dicom/" + relative;
}

TEST_F(ServiceTest, StructureSetSentAfterItsImagesLandsOnTheStoredSeries) {
  Result<v1::ImportDicomResponse> images = client_->import_dicom({sts("CT/image")});
  ASSERT_TRUE(images.ok()) << images.status().to_string();
  ASSERT_EQ(images->series_size(), 1);
  EXPECT_EQ(images->structures_size(), 0);
  const v1::Series& ct = images->series(0);

  Result<v1::ImportDicomResponse> later = client_->import_dicom({sts("CT/mask")});
  ASSERT_TRUE(later.ok()) << later.status().to_string();
  for (const v1::ImportProblem& p : later->problems()) ADD_FAILURE() << p.path() << ": " << p.message();
  EXPECT_EQ(later->series_size(), 0);
  ASSERT_EQ(later->structures_size(), 1);
  const v1::ImportedStructure& s = later->structures(0);
  EXPECT_EQ(s.referenced_series_uid(), ct.series_uid());
  EXPECT_EQ(s.structure().study_uid(), ct.study_uid());
  EXPECT_EQ(s.structure().patient_id(), "STS_002");
  EXPECT_EQ(s.voxel_count(), 17090);  // as when imported with its images

  // Its PET structure set references a series soiq does not have: nothing to import, said so.
  Result<v1::ImportDicomResponse> orphan = client_->import_dicom({sts("PET/mask")});
  ASSERT_FALSE(orphan.ok());
  EXPECT_EQ(orphan.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(orphan.status().message().find("not among the imported files"), std::string::npos)
      << orphan.status().message();
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->structures(), 1);
}

}  // namespace
}  // namespace soiq::testing

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
