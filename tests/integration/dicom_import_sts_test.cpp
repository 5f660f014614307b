// ImportDicom through a real soiqd: the STS_002 CT and PET with their RT Structure Sets, a reimport
// that updates in place, features on the patient's own grids and images, and a structure set sent
// after its images.

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "core/io/read_image.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/sts_query.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

const v1::Series* series_of_modality(const v1::ImportDicomResponse& r, const std::string& modality) {
  for (const v1::Series& s : r.series())
    if (s.modality() == modality) return &s;
  return nullptr;
}

TEST_F(ServiceTest, ImportsSts002WithItsSeriesAndStructures) {
  Result<v1::ImportDicomResponse> r = client_->import_dicom({test_data("sts/STS_002/dicom")});
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
  Result<v1::ImportDicomResponse> first = client_->import_dicom({test_data("sts/STS_002/dicom")});
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

  Result<v1::ImportDicomResponse> again = client_->import_dicom({test_data("sts/STS_002/dicom")});
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
  Result<v1::ImportDicomResponse> r = client_->import_dicom({test_data("sts/STS_002/dicom")});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const v1::Series* ct = series_of_modality(*r, "CT");
  ASSERT_NE(ct, nullptr);
  const v1::ImportedStructure* on_ct = nullptr;
  for (const v1::ImportedStructure& s : r->structures())
    if (s.referenced_series_uid() == ct->series_uid()) on_ct = &s;
  ASSERT_NE(on_ct, nullptr);

  Result<Image> mask = read_image(test_data("sts/STS_002/CT_mask.nii.gz"));
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
