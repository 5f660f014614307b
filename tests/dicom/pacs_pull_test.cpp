// Tests of dicom/pacs_*.h against a real PACS (tests/dicom/pacs_fixture.h): C-GET into a
// folder and import, compressed transfer syntaxes, C-STORE.

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "dicom/import_dicom.h"
#include "dicom/pacs_client.h"
#include "pacs_fixture.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
using testing::DcmqrscpProcess;
using testing::TempDir;

class PacsPull : public LoadedPacs {};

std::set<std::string> sop_instance_uids_under(const std::string& dir) {
  std::set<std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    DcmFileFormat f;
    if (f.loadFile(e.path().c_str()).bad()) continue;
    OFString uid;
    if (f.getDataset()->findAndGetOFString(DCM_SOPInstanceUID, uid).good()) out.insert(uid.c_str());
  }
  return out;
}

// --- C-GET ------------------------------------------------------------------------------------

TEST_F(PacsPull, PullWritesEveryInstanceOfTheStudyAndImportsLikeTheOriginals) {
  TempDir dest;
  int progress_calls = 0;
  auto r = pacs_pull(peer(), kStsStudyUid, dest.file("study"), [&](const PacsPullProgress& p) {
    ++progress_calls;
    EXPECT_EQ(p.received, progress_calls);
    return true;
  });
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->completed, kStsFiles);
  EXPECT_EQ(r->failed, 0);
  EXPECT_EQ(r->paths.size(), static_cast<size_t>(kStsFiles));
  EXPECT_EQ(progress_calls, kStsFiles);
  EXPECT_EQ(sop_instance_uids_under(dest.file("study")), sop_instance_uids_under(data_dir("sts/STS_002/dicom")));

  auto pulled = import_dicom({dest.file("study")});
  auto original = import_dicom({data_dir("sts/STS_002/dicom")});
  ASSERT_TRUE(pulled.ok()) << pulled.status().to_string();
  ASSERT_TRUE(original.ok()) << original.status().to_string();
  EXPECT_TRUE(pulled->problems.empty());
  ASSERT_EQ(pulled->images.size(), 2u);  // CT and PET
  ASSERT_EQ(pulled->images.size(), original->images.size());
  for (const SeriesImage& o : original->images) {
    const SeriesImage* p = pulled->find_image(o.series_uid);
    ASSERT_NE(p, nullptr) << o.series_uid;
    EXPECT_EQ(p->modality, o.modality);
    EXPECT_EQ(p->image.geometry, o.image.geometry);
    EXPECT_EQ(p->image.voxels, o.image.voxels);
  }
  ASSERT_EQ(pulled->structure_sets.size(), 2u);
  ASSERT_EQ(pulled->structure_sets.size(), original->structure_sets.size());
  for (const ImportedStructureSet& o : original->structure_sets) {
    const auto p =
        std::find_if(pulled->structure_sets.begin(), pulled->structure_sets.end(),
                     [&](const ImportedStructureSet& s) { return s.sop_instance_uid == o.sop_instance_uid; });
    ASSERT_NE(p, pulled->structure_sets.end()) << o.sop_instance_uid;
    EXPECT_EQ(p->referenced_series_uid, o.referenced_series_uid);
    EXPECT_EQ(p->converted.structures.size(), o.converted.structures.size());
    EXPECT_GE(p->converted.structures.size(), 1u);
  }
}

TEST_F(PacsPull, PullOfUnknownStudyIsNotFound) {
  TempDir dest;
  auto r = pacs_pull(peer(), "1.2.3.4.5.6.7.8.9", dest.file("none"));
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound) << r.status().to_string();
  EXPECT_NE(r.status().message().find("study 1.2.3.4.5.6.7.8.9 has no instances on PACS 'SOIQTEST'"), std::string::npos)
      << r.status().message();
}

TEST_F(PacsPull, PullCancelledByProgressIsCancelled) {
  TempDir dest;
  auto r =
      pacs_pull(peer(), kStsStudyUid, dest.file("study"), [](const PacsPullProgress& p) { return p.received < 5; });
  EXPECT_EQ(r.status().code(), StatusCode::kCancelled) << r.status().to_string();
  EXPECT_NE(r.status().message().find("after 5 instances"), std::string::npos) << r.status().message();
  EXPECT_TRUE(pacs_echo(peer()).ok());
}

TEST_F(PacsPull, PullWithBadStudyUidIsInvalidArgument) {
  TempDir dest;
  auto r = pacs_pull(peer(), "1.2.3/../4", dest.file("x"));
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("study_uid"), std::string::npos);
}

// The PACS dies in the middle of the transfer: an error, never a partial success.
TEST(PacsBroken, PullWhenThePacsDiesMidwayIsUnavailable) {
  DcmqrscpProcess pacs;
  const std::string error = pacs.start();
  if (error.rfind("not installed", 0) == 0) GTEST_SKIP() << error;
  ASSERT_EQ(error, "");
  ASSERT_EQ(pacs.load({data_dir("sts/STS_002/dicom")}), "");
  TempDir dest;
  PacsPeer p = pacs.peer();
  p.timeout_seconds = 5;
  auto r = pacs_pull(p, kStsStudyUid, dest.file("study"), [&](const PacsPullProgress& progress) {
    if (progress.received == 3) pacs.kill_now();
    return true;
  });
  EXPECT_EQ(r.status().code(), StatusCode::kUnavailable) << r.status().to_string();
  EXPECT_NE(r.status().message().find("C-GET of study"), std::string::npos) << r.status().message();
}

// --- C-STORE ----------------------------------------------------------------------------------

// A PACS that stores JPEG-LS (dcmqrscp +xt keeps what it receives) and cannot convert it: the C-GET
// accepts it as it is, and the pulled series imports with the voxels of the original files.
TEST(PacsCompressed, JpegLsStudyIsPulledAsStoredAndImportsExactly) {
  DcmqrscpProcess pacs;
  const std::string error = pacs.start({"+xt"});
  if (error.rfind("not installed", 0) == 0) GTEST_SKIP() << error;
  ASSERT_EQ(error, "");
  const std::string compressed = data_dir("sts/STS_008/dicom_jpegls/CT");
  ASSERT_EQ(pacs.load({compressed}, {"-xt"}), "");
  auto studies = pacs_find(pacs.peer(), PacsQuery{});
  ASSERT_TRUE(studies.ok()) << studies.status().to_string();
  ASSERT_EQ(studies->size(), 1u);
  TempDir dest;
  auto pulled = pacs_pull(pacs.peer(), studies->front().study_uid, dest.file("study"));
  ASSERT_TRUE(pulled.ok()) << pulled.status().to_string() << "\n" << pacs.output();
  EXPECT_EQ(pulled->failed, 0);
  DcmFileFormat first;
  ASSERT_TRUE(first.loadFile(pulled->paths.front().c_str()).good());
  const bool any_compressed = std::any_of(pulled->paths.begin(), pulled->paths.end(), [](const std::string& p) {
    DcmFileFormat f;
    return f.loadFile(p.c_str()).good() && DcmXfer(f.getDataset()->getOriginalXfer()).isEncapsulated();
  });
  EXPECT_TRUE(any_compressed) << "the PACS sent no compressed instance: the test proves nothing";
  auto from_pacs = import_dicom({dest.file("study")});
  auto from_files = import_dicom({compressed});
  ASSERT_TRUE(from_pacs.ok()) << from_pacs.status().to_string();
  ASSERT_TRUE(from_files.ok()) << from_files.status().to_string();
  for (const auto& p : from_pacs->problems) ADD_FAILURE() << p.status.to_string();
  ASSERT_EQ(from_pacs->images.size(), 1u);
  ASSERT_EQ(from_files->images.size(), 1u);
  EXPECT_EQ(from_pacs->images[0].image.geometry, from_files->images[0].image.geometry);
  EXPECT_EQ(from_pacs->images[0].image.voxels, from_files->images[0].image.voxels);
  ASSERT_EQ(from_pacs->structure_sets.size(), 1u);
  EXPECT_EQ(voxel_count(from_pacs->structure_sets[0].converted.structures.at(0).volume),
            voxel_count(from_files->structure_sets[0].converted.structures.at(0).volume));
}

TEST(PacsStore, StoredFileIsFoundAndPulledBack) {
  DcmqrscpProcess pacs;
  const std::string error = pacs.start();
  if (error.rfind("not installed", 0) == 0) GTEST_SKIP() << error;
  ASSERT_EQ(error, "");
  PacsQuery q;
  q.study_uid = kMrSmallStudyUid;
  auto before = pacs_find(pacs.peer(), q);
  ASSERT_TRUE(before.ok()) << before.status().to_string();
  EXPECT_EQ(before->size(), 0u);

  const Status s = pacs_store(pacs.peer(), {data_dir("dicom/MR_small.dcm"), data_dir("dicom/CT_small.dcm")});
  ASSERT_TRUE(s.ok()) << s.to_string();

  auto after = pacs_find(pacs.peer(), q);
  ASSERT_TRUE(after.ok()) << after.status().to_string();
  ASSERT_EQ(after->size(), 1u);
  EXPECT_EQ((*after)[0].patient_id, "4MR1");
  EXPECT_EQ((*after)[0].study_date, "20040826");

  TempDir dest;
  auto pulled = pacs_pull(pacs.peer(), kMrSmallStudyUid, dest.file("mr"));
  ASSERT_TRUE(pulled.ok()) << pulled.status().to_string();
  EXPECT_EQ(sop_instance_uids_under(dest.file("mr")),
            (std::set<std::string>{"1.3.6.1.4.1.5962.1.1.4.1.1.20040826185059.5457"}));
}

TEST(PacsStore, MissingOrNonDicomFileIsNamedBeforeAnythingIsSent) {
  PacsPeer p{"NOBODY", "127.0.0.1", testing::free_loopback_port()};  // never contacted
  Status missing = pacs_store(p, {data_dir("dicom/CT_small.dcm"), data_dir("dicom/no_such.dcm")});
  EXPECT_EQ(missing.code(), StatusCode::kNotFound) << missing.to_string();
  EXPECT_NE(missing.message().find("no_such.dcm"), std::string::npos);
  Status not_dicom = pacs_store(p, {data_dir("sts/LICENSE.md")});
  EXPECT_EQ(not_dicom.code(), StatusCode::kDataLoss) << not_dicom.to_string();
  EXPECT_NE(not_dicom.message().find("LICENSE.md"), std::string::npos);
  EXPECT_EQ(pacs_store(p, {}).code(), StatusCode::kInvalidArgument);
}

TEST_F(PacsPull, StoreOfSopClassThePacsRefusesIsFailedPreconditionNamingTheFile) {
  // A file of a SOP class dcmqrscp does not accept as SCP (Modality Worklist, a query model, as
  // "storage" class): no presentation context is accepted for it.
  TempDir dir;
  DcmFileFormat f;
  DcmDataset* ds = f.getDataset();
  ds->putAndInsertString(DCM_SOPClassUID, UID_FINDModalityWorklistInformationModel);
  ds->putAndInsertString(DCM_SOPInstanceUID, "1.2.826.0.1.3680043.8.498.99.1");
  ds->putAndInsertString(DCM_StudyInstanceUID, "1.2.826.0.1.3680043.8.498.99");
  ds->putAndInsertString(DCM_PatientID, "X");
  ASSERT_TRUE(f.saveFile(dir.file("odd.dcm").c_str(), EXS_LittleEndianExplicit).good());
  const Status s = pacs_store(peer(), {dir.file("odd.dcm")});
  EXPECT_EQ(s.code(), StatusCode::kFailedPrecondition) << s.to_string();
  EXPECT_NE(s.message().find("odd.dcm"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace soiq::dicom
