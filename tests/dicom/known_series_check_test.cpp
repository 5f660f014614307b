// Structure sets and SEGs sent without their images, converted on a series the caller already
// holds (dicom/import_dicom.h FindKnownSeries, dicom/known_series_check.h): the same voxels as when
// sent with the images, and refused for another patient or another frame of reference.

#include "dicom/known_series_check.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/base/run_length_volume.h"
#include "dicom/import_dicom.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"
#include "seg_source_of.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
using testing::TempDir;

// STS_002's CT imported with its RT Structure Set: the reference, and the series to "hold".
struct Held {
  DicomImport full;
  KnownSeries ct;
  RunLengthVolume gtv;
};

Held held_sts_ct() {
  Held h;
  auto imported = import_dicom({data_dir("sts/STS_002/dicom/CT")});
  EXPECT_TRUE(imported.ok()) << imported.status().to_string();
  h.full = std::move(imported).value();
  const ImportedStructureSet& set = h.full.structure_sets.at(0);
  const SeriesImage* image = h.full.find_image(set.referenced_series_uid);
  const DicomSeries* series = h.full.scan.find_series(set.referenced_series_uid);
  const DicomStudy* study = h.full.scan.find_study(series->study_uid);
  h.ct = {image->series_uid, study->study_uid, study->patient_id, series->frame_of_reference_uid,
          image->image.geometry};
  h.gtv = set.converted.structures.at(0).volume;
  return h;
}

FindKnownSeries holding(const KnownSeries& k) {
  return [k](const std::string& uid) -> std::optional<KnownSeries> {
    if (uid == k.series_uid) return k;
    return std::nullopt;
  };
}

const std::string kRtAlone = "sts/STS_002/dicom/CT/mask";

TEST(KnownSeries, RtStructureSetAloneIsConvertedOnTheHeldSeriesWithTheSameVoxels) {
  const Held h = held_sts_ct();
  auto alone = import_dicom({data_dir(kRtAlone)}, kDefaultMaxVoxels, holding(h.ct));
  ASSERT_TRUE(alone.ok()) << alone.status().to_string();
  for (const auto& p : alone->problems) ADD_FAILURE() << p.status.to_string();
  ASSERT_EQ(alone->structure_sets.size(), 1u);
  const ImportedStructureSet& set = alone->structure_sets[0];
  EXPECT_TRUE(set.on_known_series);
  EXPECT_EQ(set.referenced_series_uid, h.ct.series_uid);
  auto same = compare(set.converted.structures.at(0).volume, h.gtv);
  ASSERT_TRUE(same.ok()) << same.status().to_string();
  EXPECT_EQ(same->only_a + same->only_b, 0);
  EXPECT_EQ(same->count_a, 17090);
}

TEST(KnownSeries, WithoutTheHeldSeriesTheStructureSetIsNotFound) {
  auto alone = import_dicom({data_dir(kRtAlone)});
  ASSERT_TRUE(alone.ok()) << alone.status().to_string();
  EXPECT_TRUE(alone->structure_sets.empty());
  ASSERT_EQ(alone->problems.size(), 1u);
  EXPECT_EQ(alone->problems[0].status.code(), StatusCode::kNotFound);
}

TEST(KnownSeries, HeldSeriesOfAnotherPatientOrFrameIsRefusedNamingBoth) {
  Held h = held_sts_ct();
  KnownSeries other_patient = h.ct;
  other_patient.patient_id = "SOMEONE_ELSE";
  auto a = import_dicom({data_dir(kRtAlone)}, kDefaultMaxVoxels, holding(other_patient));
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  EXPECT_TRUE(a->structure_sets.empty());
  ASSERT_EQ(a->problems.size(), 1u);
  EXPECT_EQ(a->problems[0].status.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(a->problems[0].status.message().find("'STS_002'"), std::string::npos) << a->problems[0].status.message();
  EXPECT_NE(a->problems[0].status.message().find("'SOMEONE_ELSE'"), std::string::npos);

  KnownSeries other_frame = h.ct;
  other_frame.frame_of_reference_uid = "1.2.3.4";
  auto b = import_dicom({data_dir(kRtAlone)}, kDefaultMaxVoxels, holding(other_frame));
  ASSERT_TRUE(b.ok()) << b.status().to_string();
  EXPECT_TRUE(b->structure_sets.empty());
  ASSERT_EQ(b->problems.size(), 1u);
  EXPECT_NE(b->problems[0].status.message().find("1.2.3.4"), std::string::npos) << b->problems[0].status.message();
}

TEST(KnownSeries, SegAloneIsReadOnTheHeldSeriesWithTheSameVoxels) {
  const Held h = held_sts_ct();
  auto source = testing::seg_source_of(h.full, h.ct.series_uid);
  ASSERT_TRUE(source.ok()) << source.status().to_string();
  SegSegment segment;
  segment.label = "GTV";
  segment.volume = h.gtv;
  auto written = write_seg(*source, {segment});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  std::ofstream(tmp.file("seg.dcm"), std::ios::binary) << written->bytes;
  auto alone = import_dicom({tmp.path().string()}, kDefaultMaxVoxels, holding(h.ct));
  ASSERT_TRUE(alone.ok()) << alone.status().to_string();
  for (const auto& p : alone->problems) ADD_FAILURE() << p.status.to_string();
  ASSERT_EQ(alone->structure_sets.size(), 1u);
  EXPECT_TRUE(alone->structure_sets[0].on_known_series);
  auto same = compare(alone->structure_sets[0].converted.structures.at(0).volume, h.gtv);
  ASSERT_TRUE(same.ok()) << same.status().to_string();
  EXPECT_EQ(same->only_a + same->only_b, 0);

  KnownSeries other_patient = h.ct;
  other_patient.patient_id = "SOMEONE_ELSE";
  auto refused = import_dicom({tmp.path().string()}, kDefaultMaxVoxels, holding(other_patient));
  ASSERT_TRUE(refused.ok());
  EXPECT_TRUE(refused->structure_sets.empty());
  ASSERT_EQ(refused->problems.size(), 1u);
  EXPECT_EQ(refused->problems[0].status.code(), StatusCode::kInvalidArgument);
}

TEST(KnownSeriesCheck, AbsentValuesAreNotCompared) {
  const KnownSeries held{"1.2.3", "1.2", "P1", "9.9", {}};
  EXPECT_TRUE(check_same_patient_and_frame("x", "", {}, held).ok());
  EXPECT_TRUE(check_same_patient_and_frame("x", "P1", {"8.8", "9.9"}, held).ok());
  EXPECT_FALSE(check_same_patient_and_frame("x", "P2", {}, held).ok());
  EXPECT_FALSE(check_same_patient_and_frame("x", "", {"8.8"}, held).ok());
  KnownSeries unknown_frame = held;
  unknown_frame.frame_of_reference_uid = "";
  EXPECT_TRUE(check_same_patient_and_frame("x", "P1", {"8.8"}, unknown_frame).ok());
}

}  // namespace
}  // namespace soiq::dicom
