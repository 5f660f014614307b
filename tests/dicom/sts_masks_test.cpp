// RT Structure Sets of the STS patients converted by dicom/ equal, voxel for voxel, the NIfTI masks
// shipped beside them (docs/DESIGN.md step 7: a voxel-centre even-odd fill reproduces them exactly).
// All 4 patients x CT, MR T1, PET are in tests/data (see series_dir); SOIQ_STS_DICOM_DIR=
// ../shared/data/sts/dicom runs the same cases on the uncompressed originals.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "core/base/run_length_volume.h"
#include "core/io/read_image.h"
#include "dicom/import_dicom.h"
#include "dicom_test_support.h"

namespace soiq::dicom {
namespace sts_masks_test {

struct StsCase {
  std::string patient, modality;  // modality folder: CT, MR_T1, PET
};

void PrintTo(const StsCase& c, std::ostream* os) { *os << c.patient << "/" << c.modality; }

// tests/data keeps STS_002's CT and PET as they came (sts/STS_002/dicom) and every other series
// with its pixels JPEG-LS lossless compressed (sts/STS_xxx/dicom_jpegls; 13 MB instead of 24), so
// these cases also prove that compressed series import exactly.
std::string series_dir(const StsCase& c) {
  const char* env = std::getenv("SOIQ_STS_DICOM_DIR");
  if (env) return std::string(env) + "/" + c.patient + "/" + c.modality;
  const std::string plain = testing::data_dir("sts/" + c.patient + "/dicom/" + c.modality);
  if (std::filesystem::exists(plain)) return plain;
  return testing::data_dir("sts/" + c.patient + "/dicom_jpegls/" + c.modality);
}

class StsMasks : public ::testing::TestWithParam<StsCase> {};

TEST_P(StsMasks, StructureSetEqualsTheShippedMaskVoxelForVoxel) {
  const StsCase& c = GetParam();
  const std::string dir = series_dir(c);
  ASSERT_TRUE(std::filesystem::exists(dir)) << dir << " is missing (tests/data/sts holds every case)";
  auto imported = import_dicom({dir});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  for (const auto& p : imported->problems) ADD_FAILURE() << p.status.to_string();
  ASSERT_EQ(imported->images.size(), 1u);
  ASSERT_EQ(imported->structure_sets.size(), 1u);
  const auto& set = imported->structure_sets[0];
  EXPECT_EQ(set.referenced_series_uid, imported->images[0].series_uid);
  ASSERT_EQ(set.converted.structures.size(), 1u);
  const ImportedStructure& gtv = set.converted.structures[0];
  EXPECT_EQ(gtv.name.rfind("GTV_Mass", 0), 0u) << gtv.name;  // "GTV_Mass_CT", "GTV_Mass_PET", ...
  EXPECT_EQ(gtv.contours_outside_grid, 0);

  auto nifti = read_image(
      testing::data_dir("sts/" + c.patient + "/" + (c.modality == "PET" ? "PET" : c.modality) + "_mask.nii.gz"));
  ASSERT_TRUE(nifti.ok()) << nifti.status().to_string();
  const Status same = check_same_grid(imported->images[0].image.geometry, nifti->geometry);
  ASSERT_TRUE(same.ok()) << same.to_string();
  RunLengthVolume expected = from_mask(mask_from_image(*nifti));
  expected.geometry = gtv.volume.geometry;  // same voxel centres (checked above), compared as such
  auto cmp = compare(gtv.volume, expected);
  ASSERT_TRUE(cmp.ok()) << cmp.status().to_string();
  EXPECT_GT(cmp->count_b, 0);
  EXPECT_EQ(cmp->only_a, 0) << c.patient << " " << c.modality << ": voxels only in the DICOM conversion";
  EXPECT_EQ(cmp->only_b, 0) << c.patient << " " << c.modality << ": voxels only in the NIfTI mask";
  EXPECT_FALSE(gtv.surface.triangles.empty());
}

std::vector<StsCase> cases() {
  std::vector<StsCase> out;
  for (const char* p : {"STS_002", "STS_008", "STS_012", "STS_025"})
    for (const char* m : {"CT", "MR_T1", "PET"}) out.push_back({p, m});
  return out;
}

INSTANTIATE_TEST_SUITE_P(Sts, StsMasks, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.patient + "_" + info.param.modality; });

}  // namespace sts_masks_test
}  // namespace soiq::dicom
