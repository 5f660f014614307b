// DICOM out through a real soiqd (tests/integration/pacs_service_fixture.h): a SEG exported and read
// back voxel for voxel, pushed to the PACS and found there again; SEGs of structures that have no
// DICOM source refused clearly.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "core/base/run_length_volume.h"
#include "core/geometry/primitives.h"
#include "core/io/read_image.h"
#include "dicom/pacs_pull.h"
#include "dicom/read_seg.h"
#include "tests/integration/pacs_service_fixture.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

TEST_F(PacsServiceTest, ExportedSegHoldsExactlyTheShippedMaskAndPushedItIsFoundAgain) {
  Result<v1::ImportDicomResponse> pulled = pull_sts();
  ASSERT_TRUE(pulled.ok()) << pulled.status().to_string();
  const v1::ImportedStructure* ct = on_modality(*pulled, "CT");
  ASSERT_NE(ct, nullptr);

  // Export: the SEG read back by DCMTK is the NIfTI mask shipped with the data, voxel for voxel.
  Result<Image> mask_image = read_image(test_data("sts/STS_002/CT_mask.nii.gz"));
  ASSERT_TRUE(mask_image.ok()) << mask_image.status().to_string();
  Mask mask{mask_image->geometry, {}};
  for (float v : mask_image->voxels) mask.voxels.push_back(v != 0);
  const RunLengthVolume expected = from_mask(mask);
  v1::ExportSegRequest e;
  e.add_structure_ids(ct->structure().id());
  e.set_series_description("GTV for review");
  const std::string out = dir_.file("gtv_seg.dcm");
  Result<v1::SegInfo> info = client_->export_seg(e, out);
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->referenced_series_uid(), ct->referenced_series_uid());
  EXPECT_EQ(info->study_uid(), kStsStudyUid);
  EXPECT_EQ(info->segments(), 1);
  EXPECT_EQ(info->size_bytes(), int64_t(std::filesystem::file_size(out)));
  Result<dicom::SegObject> seg = dicom::read_seg_file(out, mask.geometry);
  ASSERT_TRUE(seg.ok()) << seg.status().to_string();
  EXPECT_EQ(seg->referenced_series_uid, ct->referenced_series_uid());
  EXPECT_EQ(seg->patient_id, "STS_002");
  ASSERT_EQ(seg->segments.size(), 1u);
  EXPECT_EQ(seg->segments[0].label, ct->structure().name());
  Result<VolumeComparison> same = compare(seg->segments[0].volume, expected);
  ASSERT_TRUE(same.ok()) << same.status().to_string();
  EXPECT_EQ(same->only_a + same->only_b, 0);
  EXPECT_EQ(same->count_a, ct->voxel_count());
  EXPECT_EQ(info->frames(), int64_t(seg->segments[0].frames.size()));

  // Push: the study on the PACS now holds one more instance, and it is that SEG.
  v1::PacsPushRequest push;
  push.add_structure_ids(ct->structure().id());
  Result<v1::PacsPushResponse> pushed = client_->pacs_push(push);
  ASSERT_TRUE(pushed.ok()) << pushed.status().to_string();
  v1::PacsFindRequest find;
  find.set_study_uid(kStsStudyUid);
  Result<v1::PacsFindResponse> found = client_->pacs_find(find);
  ASSERT_TRUE(found.ok()) << found.status().to_string();
  ASSERT_EQ(found->matches_size(), 1);
  TempDir back;
  Result<dicom::PacsPullResult> files = dicom::pacs_pull(pacs_.peer(), kStsStudyUid, back.path());
  ASSERT_TRUE(files.ok()) << files.status().to_string();
  EXPECT_EQ(files->paths.size(), size_t(kStsFiles + 1));
  bool seen = false;
  for (const std::string& path : files->paths) {
    if (!contains(path, pushed->seg().sop_instance_uid())) continue;
    seen = true;
    Result<dicom::SegObject> again = dicom::read_seg_file(path, mask.geometry);
    ASSERT_TRUE(again.ok()) << again.status().to_string();
    ASSERT_EQ(again->segments.size(), 1u);
    Result<VolumeComparison> c = compare(again->segments[0].volume, expected);
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(c->only_a + c->only_b, 0);
  }
  EXPECT_TRUE(seen) << "the pushed SEG " << pushed->seg().sop_instance_uid() << " was not pulled back";

  // And through soiq: pulling the study again recognises the SEG as the structure it was exported
  // from (same study, series, name and voxels): listed as that structure, nothing stored twice.
  Result<v1::ImportDicomResponse> again = pull_sts();
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  for (const v1::ImportProblem& p : again->problems()) ADD_FAILURE() << p.path() << ": " << p.message();
  ASSERT_EQ(again->structures_size(), 3);  // the two ROIs and the SEG's segment
  int as_ct = 0;
  for (const v1::ImportedStructure& i : again->structures()) {
    EXPECT_TRUE(i.replaced()) << i.structure().name();
    EXPECT_NE(i.structure().source_uid(), pushed->seg().sop_instance_uid() + "/1");
    if (i.structure().id() != ct->structure().id()) continue;
    ++as_ct;
    EXPECT_EQ(i.voxel_count(), ct->voxel_count());
  }
  EXPECT_EQ(as_ct, 2);  // its RT Structure Set ROI and the SEG's segment
  EXPECT_EQ(client_->server_info()->structures(), 2);
}

TEST_F(PacsServiceTest, SegOfUploadedOrMixedOrUnknownStructuresIsRefusedClearly) {
  Result<v1::ImportDicomResponse> pulled = pull_sts();
  ASSERT_TRUE(pulled.ok()) << pulled.status().to_string();
  const v1::ImportedStructure* ct = on_modality(*pulled, "CT");
  const v1::ImportedStructure* pt = on_modality(*pulled, "PT");
  ASSERT_TRUE(ct && pt);
  const std::string out = dir_.file("refused.dcm");
  auto export_of = [&](std::vector<int64_t> ids, const std::string& description = "") {
    v1::ExportSegRequest e;
    for (int64_t id : ids) e.add_structure_ids(id);
    e.set_series_description(description);
    return client_->export_seg(e, out);
  };
  Result<v1::SegInfo> mixed = export_of({ct->structure().id(), pt->structure().id()});
  EXPECT_EQ(mixed.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(mixed.status().message(), "one SEG references one series")) << mixed.status().message();
  EXPECT_FALSE(std::filesystem::exists(out));

  Result<v1::SegInfo> unknown = export_of({999999});
  EXPECT_EQ(unknown.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(export_of({}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(export_of({ct->structure().id(), ct->structure().id()}).status().code(), StatusCode::kInvalidArgument);
  Result<v1::SegInfo> bad_description = export_of({ct->structure().id()}, "line\\break");
  EXPECT_EQ(bad_description.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(bad_description.status().message(), "LO")) << bad_description.status().message();

  v1::PacsPushRequest push;
  push.add_structure_ids(999999);
  EXPECT_EQ(client_->pacs_push(push).status().code(), StatusCode::kNotFound);
}

TEST_F(ServiceTest, SegOfAnUploadedStructureIsFailedPreconditionNamingImport) {
  Result<v1::UploadSurfaceResponse> up = upload(uv_sphere({0, 0, 0}, 10, 16, 32), "P1", "1.2.3", "ball");
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  v1::ExportSegRequest e;
  e.add_structure_ids(up->structure().id());
  Result<v1::SegInfo> r = client_->export_seg(e, dir_.file("x.dcm"));
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(r.status().message(), "soiq import")) << r.status().message();
}
}  // namespace
}  // namespace soiq::testing
