// DICOM SEG export (dicom/seg_export.h) and read-back (dicom/read_seg.h): round trips are lossless
// voxel for voxel on axis-aligned and oblique grids and on the real STS_002 GTV, DCMTK itself accepts
// what we write, and the study's values are copied from the source. The inputs are in
// seg_export_fixture.h; the bad inputs are in seg_export_errors_test.cpp.
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcistrmb.h>
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>

#include "core/base/run_length_volume.h"
#include "dicom/import_dicom.h"
#include "dicom/read_seg.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"
#include "seg_export_fixture.h"
#include "seg_source_of.h"
#include "seg_test_support.h"

namespace soiq::dicom {
namespace {

using testing::axis_aligned_grid;
using testing::BadInput;
using testing::data_dir;
using testing::oblique_grid;
using testing::read_back;
using testing::segment_of;
using testing::shapes;
using testing::synthetic_source;
using testing::TempDir;

std::set<int64_t> slices_with_voxels(const Mask& m) {
  std::set<int64_t> out;
  const int64_t per_slice = m.geometry.dims[0] * m.geometry.dims[1];
  for (size_t n = 0; n < m.voxels.size(); ++n)
    if (m.voxels[n]) out.insert(static_cast<int64_t>(n) / per_slice);
  return out;
}

void expect_same_voxels(const RunLengthVolume& got, const RunLengthVolume& want) {
  auto cmp = compare(got, want);
  ASSERT_TRUE(cmp.ok()) << cmp.status().to_string();
  EXPECT_GT(cmp->count_b, 0);
  EXPECT_EQ(cmp->only_a, 0) << "voxels only in the read-back SEG";
  EXPECT_EQ(cmp->only_b, 0) << "voxels lost in the SEG";
  EXPECT_EQ(got.runs, want.runs);
  EXPECT_EQ(got.line_start, want.line_start);
}

// Writes two segments on `g`, reads them back, and checks voxels, labels, frames and references.
void round_trip(const ImageGeometry& g) {
  const SegSource source = synthetic_source(g);
  const Mask a = shapes(g, 1), b = shapes(g, 99);
  SegSegment first = segment_of("GTV_Mass", from_mask(a));
  first.category = {"49755003", "SCT", "Morphologically Altered Structure"};
  first.type = {"4147007", "SCT", "Mass"};
  first.display_rgb = std::array<uint8_t, 3>{255, 0, 0};
  SegSegment second = segment_of("other structure", from_mask(b));
  second.algorithm_type = SegAlgorithmType::kManual;
  auto written = write_seg(source, {first, second});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  const std::set<int64_t> ka = slices_with_voxels(a), kb = slices_with_voxels(b);
  EXPECT_EQ(written->frame_count, static_cast<int64_t>(ka.size() + kb.size()));
  EXPECT_NE(written->series_uid, source.series_uid);

  auto back = read_back(written->bytes, g);
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  EXPECT_EQ(back->study_uid, source.study_uid);
  EXPECT_EQ(back->patient_id, source.patient_id);
  EXPECT_EQ(back->frame_of_reference_uid, source.frame_of_reference_uid);
  EXPECT_EQ(back->series_uid, written->series_uid);
  EXPECT_EQ(back->sop_instance_uid, written->sop_instance_uid);
  EXPECT_EQ(back->referenced_series_uid, source.series_uid);
  ASSERT_EQ(back->segments.size(), 2u);
  EXPECT_EQ(back->segments[0].label, "GTV_Mass");
  EXPECT_EQ(back->segments[0].type_code, "SCT:4147007");
  EXPECT_EQ(back->segments[0].algorithm_type, "SEMIAUTOMATIC");
  EXPECT_EQ(back->segments[1].label, "other structure");
  EXPECT_EQ(back->segments[1].category_code, "SCT:85756007");
  EXPECT_EQ(back->segments[1].algorithm_type, "MANUAL");
  expect_same_voxels(back->segments[0].volume, first.volume);
  expect_same_voxels(back->segments[1].volume, second.volume);

  // One frame per occupied slice, each derived from that slice's instance.
  const std::set<int64_t>* want_slices[] = {&ka, &kb};
  std::set<std::string> want_refs;
  for (int s = 0; s < 2; ++s) {
    std::set<int64_t> got;
    for (const SegFrameSource& f : back->segments[s].frames) {
      got.insert(f.k);
      EXPECT_EQ(f.source_sop_instance_uid, source.slice_sop_instance_uids[static_cast<size_t>(f.k)]) << "k=" << f.k;
    }
    EXPECT_EQ(got, *want_slices[s]);
    EXPECT_EQ(back->segments[s].frames.size(), want_slices[s]->size());
    for (int64_t k : *want_slices[s]) want_refs.insert(source.slice_sop_instance_uids[static_cast<size_t>(k)]);
  }
  const std::set<std::string> refs(back->referenced_sop_instance_uids.begin(),
                                   back->referenced_sop_instance_uids.end());
  EXPECT_EQ(refs, want_refs);
  EXPECT_EQ(back->referenced_sop_instance_uids.size(), want_refs.size());
}

TEST(SegExport, AxisAlignedAnisotropicRoundTripIsLossless) { round_trip(axis_aligned_grid()); }

TEST(SegExport, ObliqueRoundTripIsLossless) {
  const ImageGeometry g = oblique_grid();
  ASSERT_TRUE(validate_geometry(g).ok()) << validate_geometry(g).to_string();
  ASSERT_GT(std::abs(g.direction[0][1]), 0.1);  // really oblique
  round_trip(g);
}

// The GTV of the real STS_002 RT Structure Set, exported on its CT and read back; DCMTK's own SEG
// reader and plain tag reads check the file independently of read_seg.
TEST(SegExport, StsGtvOnItsCtRoundTripsAndDcmtkAcceptsIt) {
  const std::string dir = data_dir("sts/STS_002/dicom/CT");
  auto imported = import_dicom({dir});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  ASSERT_EQ(imported->structure_sets.size(), 1u);
  const ImportedStructureSet& set = imported->structure_sets[0];
  ASSERT_EQ(set.converted.structures.size(), 1u);
  const ImportedStructure& gtv = set.converted.structures[0];
  Result<SegSource> made = testing::seg_source_of(*imported, set.referenced_series_uid);
  ASSERT_TRUE(made.ok()) << made.status().to_string();
  const SegSource& source = *made;
  SegSegment segment = segment_of(gtv.name, gtv.volume);
  segment.category = {"49755003", "SCT", "Morphologically Altered Structure"};
  segment.type = {"4147007", "SCT", "Mass"};

  const auto start = std::chrono::steady_clock::now();
  auto written = write_seg(source, {segment});
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  ::testing::Test::RecordProperty("write_ms", std::to_string(ms));
  std::cout << "STS_002 GTV SEG: " << written->frame_count << " frames of " << describe(source.geometry) << ", "
            << written->bytes.size() << " bytes, written in " << ms << " ms\n";

  TempDir tmp;
  const std::string path = tmp.file("gtv_seg.dcm");
  std::ofstream(path, std::ios::binary) << written->bytes;

  auto back = read_seg_file(path, source.geometry);
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  ASSERT_EQ(back->segments.size(), 1u);
  EXPECT_EQ(back->segments[0].label, gtv.name);
  expect_same_voxels(back->segments[0].volume, gtv.volume);
  EXPECT_EQ(back->referenced_series_uid, source.series_uid);

  DcmSegmentation* raw = nullptr;
  const OFCondition loaded = DcmSegmentation::loadFile(path.c_str(), raw);
  std::unique_ptr<DcmSegmentation> seg(raw);
  ASSERT_TRUE(loaded.good()) << loaded.text();
  EXPECT_EQ(seg->getNumberOfSegments(), 1u);
  EXPECT_EQ(static_cast<int64_t>(seg->getNumberOfFrames()), written->frame_count);

  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  DcmDataset& ds = *file.getDataset();
  OFString value;
  ASSERT_TRUE(ds.findAndGetOFString(DCM_SOPClassUID, value).good());
  EXPECT_EQ(value, "1.2.840.10008.5.1.4.1.1.66.4");
  ASSERT_TRUE(ds.findAndGetOFString(DCM_Modality, value).good());
  EXPECT_EQ(value, "SEG");
  ASSERT_TRUE(ds.findAndGetOFString(DCM_StudyInstanceUID, value).good());
  EXPECT_EQ(value, OFString(source.study_uid.c_str()));
  ASSERT_TRUE(ds.findAndGetOFString(DCM_FrameOfReferenceUID, value).good());
  EXPECT_EQ(value, OFString(source.frame_of_reference_uid.c_str()));
  DcmItem* referenced = nullptr;
  ASSERT_TRUE(ds.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, referenced, 0).good());
  ASSERT_TRUE(referenced->findAndGetOFString(DCM_SeriesInstanceUID, value).good());
  EXPECT_EQ(value, OFString(source.series_uid.c_str()));
}

// --- the study's values ---

std::string tag_value(DcmDataset& ds, const DcmTagKey& tag) {
  OFString value;
  EXPECT_TRUE(ds.tagExists(tag)) << DcmTag(tag).getTagName() << " is missing";
  ds.findAndGetOFString(tag, value);
  return value.c_str();
}

DcmDataset* dataset_of(const std::string& bytes, DcmFileFormat& file) {
  DcmInputBufferStream in;
  in.setBuffer(bytes.data(), static_cast<offile_off_t>(bytes.size()));
  in.setEos();
  file.transferInit();
  EXPECT_TRUE(file.read(in).good());
  file.transferEnd();
  return file.getDataset();
}

TEST(SegExport, StudyTimeIdAndAccessionNumberAreCopiedFromTheSource) {
  BadInput in;
  auto written = write_seg(in.source, {in.segment});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  DcmFileFormat file;
  DcmDataset& ds = *dataset_of(written->bytes, file);
  EXPECT_EQ(tag_value(ds, DCM_StudyDate), "20240102");
  EXPECT_EQ(tag_value(ds, DCM_StudyTime), "101112");
  EXPECT_EQ(tag_value(ds, DCM_StudyID), "S1");
  EXPECT_EQ(tag_value(ds, DCM_AccessionNumber), "A42");
}

// Type 2: present and empty when the source has no value, or one that does not fit its VR (a
// 17-character Study ID, SH allows 16), never truncated.
TEST(SegExport, MissingOrInvalidStudyValuesAreWrittenEmpty) {
  BadInput in;
  in.source.study_time = "";
  in.source.accession_number = "";
  in.source.study_id = "IBSI_1_STS_002_CT";
  in.source.study_date = "2024-01-02";
  auto written = write_seg(in.source, {in.segment});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  DcmFileFormat file;
  DcmDataset& ds = *dataset_of(written->bytes, file);
  for (const DcmTagKey& tag : {DCM_StudyTime, DCM_AccessionNumber, DCM_StudyID, DCM_StudyDate})
    EXPECT_EQ(tag_value(ds, tag), "") << DcmTag(tag).getTagName();
}

}  // namespace
}  // namespace soiq::dicom
