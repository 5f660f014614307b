// Tests of dicom/pacs_*.h against a real PACS: DCMTK's dcmqrscp on loopback, loaded with DCMTK's
// storescu (tests/dicom/dcmqrscp_process.h). Expected values are read from the files themselves
// (tests/data/dicom/facts.json, dcmdump of tests/data/sts/STS_002).

#include "dicom/pacs_client.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/base/run_length_volume.h"
#include "tests/support/dcmqrscp_process.h"
#include "dicom/import_dicom.h"
#include "dicom_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
using testing::DcmqrscpProcess;
using testing::TempDir;

constexpr const char* kStsStudyUid = "1.3.6.1.4.1.14519.5.2.1.5168.1900.190311276211389538203367070477";
constexpr const char* kCtSmallStudyUid = "1.3.6.1.4.1.5962.1.2.1.20040119072730.12322";
constexpr const char* kMrSmallStudyUid = "1.3.6.1.4.1.5962.1.2.4.20040826185059.5457";
constexpr int kStsFiles = 98;  // 48 CT + 48 PET slices + 2 RT Structure Sets

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

std::vector<std::string> patient_ids(const std::vector<PacsMatch>& matches) {
  std::vector<std::string> out;
  for (const auto& m : matches) out.push_back(m.patient_id);
  std::sort(out.begin(), out.end());
  return out;
}

// One dcmqrscp for the read-only tests, loaded once: STS_002 (CT, PET, 2 RTSTRUCT),
// CT_small.dcm and rtstruct.dcm: 3 patients, 3 studies, 100 instances.
class Pacs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    pacs_ = new DcmqrscpProcess();
    setup_error_ = pacs_->start();
    if (setup_error_.empty())
      setup_error_ =
          pacs_->load({data_dir("sts/STS_002/dicom"), data_dir("dicom/CT_small.dcm"), data_dir("dicom/rtstruct.dcm")});
  }
  static void TearDownTestSuite() {
    delete pacs_;
    pacs_ = nullptr;
  }
  void SetUp() override {
    if (setup_error_.rfind("not installed", 0) == 0) GTEST_SKIP() << setup_error_;
    ASSERT_EQ(setup_error_, "");
  }
  static PacsPeer peer() { return pacs_->peer(); }

  static DcmqrscpProcess* pacs_;
  static std::string setup_error_;
};
DcmqrscpProcess* Pacs::pacs_ = nullptr;
std::string Pacs::setup_error_;

// --- PacsPeer ---------------------------------------------------------------------------------

TEST(PacsPeer, ValidPeerPasses) {
  PacsPeer p{"ORTHANC", "pacs.example.org", 4242};
  EXPECT_TRUE(validate_pacs_peer(p).ok());
}

TEST(PacsPeer, EachBadFieldIsInvalidArgumentNamingIt) {
  const PacsPeer good{"ORTHANC", "127.0.0.1", 4242};
  struct Case {
    PacsPeer peer;
    std::string phrase;
  };
  std::vector<Case> cases;
  cases.push_back({good, ""});
  cases.back().peer.called_ae = "";
  cases.back().phrase = "called_ae";
  cases.push_back({good, "called_ae"});
  cases.back().peer.called_ae = "SEVENTEEN_CHARS_X";
  cases.push_back({good, "called_ae"});
  cases.back().peer.called_ae = "A\\B";
  cases.push_back({good, "calling_ae"});
  cases.back().peer.calling_ae = "    ";
  cases.push_back({good, "calling_ae"});
  cases.back().peer.calling_ae = "S\xc3\x96IQ";
  cases.push_back({good, "host"});
  cases.back().peer.host = "";
  cases.push_back({good, "host"});
  cases.back().peer.host = "pacs host";
  cases.push_back({good, "port"});
  cases.back().peer.port = 0;
  cases.push_back({good, "port"});
  cases.back().peer.port = 65536;
  cases.push_back({good, "timeout_seconds"});
  cases.back().peer.timeout_seconds = 0;
  for (const auto& c : cases) {
    const Status s = validate_pacs_peer(c.peer);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << c.phrase;
    EXPECT_NE(s.message().find(c.phrase), std::string::npos) << s.message();
    // Every operation validates first, before touching the network.
    EXPECT_EQ(pacs_echo(c.peer).code(), StatusCode::kInvalidArgument);
    EXPECT_EQ(pacs_find(c.peer, PacsQuery{}).status().code(), StatusCode::kInvalidArgument);
  }
}

// --- C-ECHO -----------------------------------------------------------------------------------

TEST_F(Pacs, EchoSucceeds) { EXPECT_TRUE(pacs_echo(peer()).ok()); }

TEST_F(Pacs, EchoToClosedPortIsUnavailableNamingHostAndPortAndReturnsQuickly) {
  PacsPeer p = peer();
  p.port = testing::free_loopback_port();  // nothing listens there
  const auto t0 = std::chrono::steady_clock::now();
  const Status s = pacs_echo(p);
  const auto elapsed = std::chrono::steady_clock::now() - t0;
  EXPECT_EQ(s.code(), StatusCode::kUnavailable) << s.to_string();
  EXPECT_NE(s.message().find("127.0.0.1:" + std::to_string(p.port)), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("SOIQTEST"), std::string::npos) << s.message();
  // Refused, not timed out: well under the 10 s timeout of the peer.
  EXPECT_LT(elapsed, std::chrono::seconds(5));
}

// A peer that accepts the TCP connection and never answers: the ACSE timeout ends the call.
TEST(PacsStalled, EchoToSilentPeerIsUnavailableAfterTheTimeout) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(fd, 4), 0);  // the kernel completes handshakes; nobody ever reads
  ASSERT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len), 0);
  PacsPeer p{"SILENT", "127.0.0.1", ntohs(addr.sin_port)};
  p.timeout_seconds = 1;
  const auto t0 = std::chrono::steady_clock::now();
  const Status s = pacs_echo(p);
  const auto elapsed = std::chrono::steady_clock::now() - t0;
  ::close(fd);
  EXPECT_EQ(s.code(), StatusCode::kUnavailable) << s.to_string();
  EXPECT_NE(s.message().find("127.0.0.1:" + std::to_string(p.port)), std::string::npos) << s.message();
  EXPECT_LT(elapsed, std::chrono::seconds(15));  // no hang: bounded by the timeouts, not forever
}

TEST_F(Pacs, EchoToUnknownCalledAeIsRejectedWithTheReason) {
  PacsPeer p = peer();
  p.called_ae = "NOT_THE_PACS";
  const Status s = pacs_echo(p);
  EXPECT_EQ(s.code(), StatusCode::kPermissionDenied) << s.to_string();
  EXPECT_NE(s.message().find("rejected"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("Called AE Title Not Recognized"), std::string::npos) << s.message();
}

// --- C-FIND -----------------------------------------------------------------------------------

TEST_F(Pacs, FindAllPatientsListsTheThreeLoaded) {
  PacsQuery q;
  q.level = PacsLevel::kPatient;
  q.patient_id = "*";
  auto r = pacs_find(peer(), q);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(patient_ids(*r), (std::vector<std::string>{"1CT1", "STS_002", "tPhantom30sep"}));
}

TEST_F(Pacs, FindPatientByWildcardReturnsItsDemographics) {
  PacsQuery q;
  q.level = PacsLevel::kPatient;
  q.patient_id = "STS*";
  auto r = pacs_find(peer(), q);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  ASSERT_EQ(r->size(), 1u);
  EXPECT_EQ((*r)[0].patient_id, "STS_002");
  EXPECT_EQ((*r)[0].patient_name, "STS_002");
  EXPECT_EQ((*r)[0].patient_sex, "M");
  EXPECT_EQ((*r)[0].patient_birth_date, "");
  EXPECT_EQ((*r)[0].study_uid, "");  // PATIENT level
}

TEST_F(Pacs, FindStudyByDateRangeThatIncludesIt) {
  for (const PacsModel model : {PacsModel::kPatientRoot, PacsModel::kStudyRoot}) {
    PacsQuery q;
    q.model = model;
    q.study_date = "20060101-20061231";
    auto r = pacs_find(peer(), q);
    ASSERT_TRUE(r.ok()) << r.status().to_string();
    ASSERT_EQ(r->size(), 1u);
    const PacsMatch& m = (*r)[0];
    EXPECT_EQ(m.study_uid, kStsStudyUid);
    EXPECT_EQ(m.study_date, "20060128");
    EXPECT_EQ(m.patient_id, "STS_002");
    EXPECT_EQ(m.accession_number, "3912173256621705");
    EXPECT_FALSE(m.number_of_instances.has_value());  // dcmqrscp does not support this key
  }
}

TEST_F(Pacs, FindStudyByOpenDateRanges) {
  PacsQuery q;
  q.study_date = "20070101-";
  auto after = pacs_find(peer(), q);
  ASSERT_TRUE(after.ok()) << after.status().to_string();
  EXPECT_EQ(after->size(), 0u);

  q.study_date = "-20060128";  // inclusive: STS_002 (20060128) and CT_small (20040119)
  auto before = pacs_find(peer(), q);
  ASSERT_TRUE(before.ok()) << before.status().to_string();
  std::vector<std::string> uids;
  for (const auto& m : *before) uids.push_back(m.study_uid);
  std::sort(uids.begin(), uids.end());
  EXPECT_EQ(uids, (std::vector<std::string>{kStsStudyUid, kCtSmallStudyUid}));

  q.study_date = "20060129-20061231";
  auto excluding = pacs_find(peer(), q);
  ASSERT_TRUE(excluding.ok()) << excluding.status().to_string();
  EXPECT_EQ(excluding->size(), 0u);
}

TEST_F(Pacs, FindStudyByUidAndAccessionNumber) {
  PacsQuery q;
  q.study_uid = kCtSmallStudyUid;
  auto by_uid = pacs_find(peer(), q);
  ASSERT_TRUE(by_uid.ok()) << by_uid.status().to_string();
  ASSERT_EQ(by_uid->size(), 1u);
  EXPECT_EQ((*by_uid)[0].patient_id, "1CT1");
  EXPECT_EQ((*by_uid)[0].study_date, "20040119");
  EXPECT_EQ((*by_uid)[0].study_description, "e+1");

  q = PacsQuery{};
  q.model = PacsModel::kStudyRoot;
  q.accession_number = "3912173256621705";
  auto by_accession = pacs_find(peer(), q);
  ASSERT_TRUE(by_accession.ok()) << by_accession.status().to_string();
  ASSERT_EQ(by_accession->size(), 1u);
  EXPECT_EQ((*by_accession)[0].study_uid, kStsStudyUid);
}

TEST_F(Pacs, FindBeyondMaxMatchesIsResourceExhausted) {
  PacsQuery q;
  q.level = PacsLevel::kPatient;
  q.max_matches = 2;  // 3 patients
  auto r = pacs_find(peer(), q);
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted) << r.status().to_string();
  EXPECT_NE(r.status().message().find("more than 2 matches"), std::string::npos) << r.status().message();
  q.max_matches = 3;  // exactly as many is fine
  EXPECT_TRUE(pacs_find(peer(), q).ok());
  // The aborted association left the PACS usable.
  EXPECT_TRUE(pacs_echo(peer()).ok());
}

TEST_F(Pacs, FindByModalityFailsWhenThePacsIgnoresModalitiesInStudy) {
  PacsQuery q;
  q.modalities = "MR";  // no MR study loaded; dcmqrscp would match all three
  auto r = pacs_find(peer(), q);
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition) << r.status().to_string();
  EXPECT_NE(r.status().message().find("Modalities in Study"), std::string::npos) << r.status().message();
}

TEST_F(Pacs, BadQueriesAreInvalidArgumentNamingTheField) {
  struct Case {
    PacsQuery query;
    std::string phrase;
  };
  std::vector<Case> cases(7);
  cases[0].query.study_date = "2006-01-28";
  cases[0].phrase = "study_date";
  cases[1].query.study_date = "20061301-";
  cases[1].phrase = "study_date";
  cases[2].query.study_date = "20070101-20060101";
  cases[2].phrase = "ends before it starts";
  cases[3].query.level = PacsLevel::kPatient;
  cases[3].query.study_date = "20060128";
  cases[3].phrase = "STUDY level";
  cases[4].query.patient_id = "A\\B";
  cases[4].phrase = "patient_id";
  cases[5].query.modalities = "ct";
  cases[5].phrase = "modalities";
  cases[6].query.level = PacsLevel::kPatient;
  cases[6].query.model = PacsModel::kStudyRoot;
  cases[6].phrase = "Study Root";
  for (const auto& c : cases) {
    auto r = pacs_find(peer(), c.query);
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << c.phrase;
    EXPECT_NE(r.status().message().find(c.phrase), std::string::npos) << r.status().message();
  }
}

// --- C-GET ------------------------------------------------------------------------------------

TEST_F(Pacs, PullWritesEveryInstanceOfTheStudyAndImportsLikeTheOriginals) {
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

TEST_F(Pacs, PullOfUnknownStudyIsNotFound) {
  TempDir dest;
  auto r = pacs_pull(peer(), "1.2.3.4.5.6.7.8.9", dest.file("none"));
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound) << r.status().to_string();
  EXPECT_NE(r.status().message().find("study 1.2.3.4.5.6.7.8.9 has no instances on PACS 'SOIQTEST'"), std::string::npos)
      << r.status().message();
}

TEST_F(Pacs, PullCancelledByProgressIsCancelled) {
  TempDir dest;
  auto r =
      pacs_pull(peer(), kStsStudyUid, dest.file("study"), [](const PacsPullProgress& p) { return p.received < 5; });
  EXPECT_EQ(r.status().code(), StatusCode::kCancelled) << r.status().to_string();
  EXPECT_NE(r.status().message().find("after 5 instances"), std::string::npos) << r.status().message();
  EXPECT_TRUE(pacs_echo(peer()).ok());
}

TEST_F(Pacs, PullWithBadStudyUidIsInvalidArgument) {
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

TEST_F(Pacs, StoreOfSopClassThePacsRefusesIsFailedPreconditionNamingTheFile) {
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
