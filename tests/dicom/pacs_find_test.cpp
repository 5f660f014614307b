// Tests of dicom/pacs_*.h against a real PACS (tests/dicom/pacs_fixture.h): the peer's
// validation, C-ECHO and C-FIND.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "dicom/pacs_client.h"
#include "pacs_fixture.h"

namespace soiq::dicom {
namespace {

class Pacs : public LoadedPacs {};

std::vector<std::string> patient_ids(const std::vector<PacsMatch>& matches) {
  std::vector<std::string> out;
  for (const auto& m : matches) out.push_back(m.patient_id);
  std::sort(out.begin(), out.end());
  return out;
}

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

}  // namespace
}  // namespace soiq::dicom
