// DICOM in from a PACS through a real soiqd (soiqd --pacs) against a real PACS on loopback
// (tests/integration/pacs_service_fixture.h): echo, find with wildcards and date ranges, pull into
// soiq and query what came, and the failures: no PACS configured, a PACS that is down, one that
// refuses our association, one that dies midway, a client that cancels.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <thread>

#include "tests/integration/pacs_service_fixture.h"
#include "tests/integration/sts_query.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

TEST_F(PacsServiceTest, EchoNamesThePacs) {
  Result<v1::PacsEchoResponse> r = client_->pacs_echo();
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->pacs(), "PACS 'SOIQTEST' at 127.0.0.1:" + std::to_string(pacs_.port()));
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->pacs(), r->pacs());
}

TEST_F(PacsServiceTest, FindPatientsByWildcardAndStudiesByDateRange) {
  v1::PacsFindRequest patients;
  patients.set_level(v1::PACS_LEVEL_PATIENT);
  patients.set_patient_id("STS*");
  Result<v1::PacsFindResponse> p = client_->pacs_find(patients);
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  ASSERT_EQ(p->matches_size(), 1);
  EXPECT_EQ(p->matches(0).patient_id(), "STS_002");
  EXPECT_EQ(p->matches(0).patient_sex(), "M");

  v1::PacsFindRequest studies;  // the STS_002 study is of 2006-01-28
  studies.set_study_date("20060101-20060131");
  Result<v1::PacsFindResponse> in = client_->pacs_find(studies);
  ASSERT_TRUE(in.ok()) << in.status().to_string();
  ASSERT_EQ(in->matches_size(), 1);
  EXPECT_EQ(in->matches(0).study_uid(), kStsStudyUid);
  EXPECT_EQ(in->matches(0).study_date(), "20060128");
  // dcmqrscp does not return Number of Study Related Instances; a PACS that does must say 98.
  EXPECT_TRUE(in->matches(0).number_of_instances() == -1 || in->matches(0).number_of_instances() == kStsFiles);

  studies.set_study_date("20060129-");
  Result<v1::PacsFindResponse> after = client_->pacs_find(studies);
  ASSERT_TRUE(after.ok()) << after.status().to_string();
  for (const v1::PacsMatch& m : after->matches()) EXPECT_NE(m.study_uid(), kStsStudyUid);

  v1::PacsFindRequest all;
  Result<v1::PacsFindResponse> both = client_->pacs_find(all);
  ASSERT_TRUE(both.ok()) << both.status().to_string();
  EXPECT_EQ(both->matches_size(), 2);  // STS_002 and CT_small
  all.set_max_matches(1);
  EXPECT_EQ(client_->pacs_find(all).status().code(), StatusCode::kResourceExhausted);
}

TEST_F(PacsServiceTest, BadFindKeysAreInvalidArgument) {
  v1::PacsFindRequest r;
  r.set_study_date("2006-01-28");
  Result<v1::PacsFindResponse> bad_date = client_->pacs_find(r);
  EXPECT_EQ(bad_date.status().code(), StatusCode::kInvalidArgument);
  v1::PacsFindRequest study_key_at_patient_level;
  study_key_at_patient_level.set_level(v1::PACS_LEVEL_PATIENT);
  study_key_at_patient_level.set_study_uid(kStsStudyUid);
  EXPECT_EQ(client_->pacs_find(study_key_at_patient_level).status().code(), StatusCode::kInvalidArgument);
  v1::PacsFindRequest too_many;
  too_many.set_max_matches(10001);
  EXPECT_EQ(client_->pacs_find(too_many).status().code(), StatusCode::kInvalidArgument);
}

TEST_F(PacsServiceTest, PulledStudyIsStoredAsItsFilesImportAndIsQueried) {
  int events = 0, last_received = 0;
  Result<v1::ImportDicomResponse> pulled = pull_sts([&](const v1::PacsPullProgress& p) {
    ++events;
    EXPECT_EQ(p.studies(), 1);
    EXPECT_GT(p.received(), last_received);
    last_received = p.received();
    return true;
  });
  ASSERT_TRUE(pulled.ok()) << pulled.status().to_string();
  EXPECT_EQ(events, kStsFiles);
  EXPECT_EQ(pulled->files_received(), kStsFiles);
  EXPECT_EQ(pulled->series_size(), 2);
  ASSERT_EQ(pulled->structures_size(), 2);
  for (const v1::ImportProblem& p : pulled->problems()) ADD_FAILURE() << p.path() << ": " << p.message();

  // The same files imported directly give the same structures (same voxels): the pull is lossless.
  TempDir other;
  SoiqdProcess direct_server(other.file("direct.db"));
  client::ClientOptions o;
  o.address = direct_server.address();
  Result<client::Client> direct_client = client::Client::connect(o);
  ASSERT_TRUE(direct_client.ok());
  Result<v1::ImportDicomResponse> direct = direct_client->import_dicom({test_data("sts/STS_002/dicom")});
  ASSERT_TRUE(direct.ok()) << direct.status().to_string();
  for (const char* modality : {"CT", "PT"}) {
    const v1::ImportedStructure* a = on_modality(*pulled, modality);
    const v1::ImportedStructure* b = on_modality(*direct, modality);
    ASSERT_TRUE(a && b) << modality;
    EXPECT_EQ(a->voxel_count(), b->voxel_count()) << modality;
    EXPECT_EQ(a->structure().name(), b->structure().name());
    EXPECT_EQ(a->structure().source_uid(), b->structure().source_uid());
  }

  // Stage 1 on the pulled demographics, stage 2 on the pulled images.
  v1::QueryRequest q = gtv_mean_pet_query();
  q.mutable_stage1()->set_min_age_years(50);
  Result<QueryResult> s = run_query(*client_, q);
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  for (const v1::QueryRow& row : s->rows) EXPECT_EQ(row.patient().patient_id(), "STS_002");
  EXPECT_EQ(s->rows.size(), 2u);
  EXPECT_EQ(s->summary.failed(), 0);

  // Pulled again: the same structures, updated in place.
  Result<v1::ImportDicomResponse> again = pull_sts();
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  for (const v1::ImportedStructure& i : again->structures()) EXPECT_TRUE(i.replaced()) << i.structure().name();
  EXPECT_EQ(client_->server_info()->structures(), 2);
}

TEST_F(PacsServiceTest, PullByPatientTakesEveryStudyOfThePatient) {
  v1::PacsPullRequest r;
  r.set_patient_id("STS_002");
  Result<v1::ImportDicomResponse> pulled = client_->pacs_pull(r);
  ASSERT_TRUE(pulled.ok()) << pulled.status().to_string();
  ASSERT_EQ(pulled->studies_size(), 1);
  EXPECT_EQ(pulled->studies(0).study_uid(), kStsStudyUid);
  EXPECT_EQ(pulled->structures_size(), 2);

  r.set_patient_id("NOBODY");
  EXPECT_EQ(client_->pacs_pull(r).status().code(), StatusCode::kNotFound);
  r.set_patient_id("STS*");
  Result<v1::ImportDicomResponse> wildcard = client_->pacs_pull(r);
  EXPECT_EQ(wildcard.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(wildcard.status().message(), "wildcard")) << wildcard.status().message();
  r.add_study_uids(kStsStudyUid);  // and a patient: one or the other
  EXPECT_EQ(client_->pacs_pull(r).status().code(), StatusCode::kInvalidArgument);
}

TEST_F(PacsServiceTest, PullOfUnknownStudyIsNotFoundAndStoresNothing) {
  v1::PacsPullRequest r;
  r.add_study_uids("1.2.3.4.5.6.7.8.9");
  Result<v1::ImportDicomResponse> pulled = client_->pacs_pull(r);
  EXPECT_EQ(pulled.status().code(), StatusCode::kNotFound);
  EXPECT_TRUE(contains(pulled.status().message(), "1.2.3.4.5.6.7.8.9")) << pulled.status().message();
  EXPECT_EQ(stored_structures(), 0);
}

// The pulled CT (161x143x48) and PET (30x27x48) are admitted together, before either is decoded:
// 12 bytes per voxel plus one slice at 4 bytes per pixel each, 13,823,140 bytes, and their 96
// original files kept (twice their 2,580,864 bytes and 16 KiB each for metadata): 20,557,732 bytes.
TEST_F(PacsServiceTest, PullThatCanNeverFitTheMemoryBudgetIsRefusedAndStoresNothing) {
  start_with_pacs(pacs_address(), {"--memory-budget", "4M"});
  Result<v1::ImportDicomResponse> pulled = pull_sts();
  ASSERT_FALSE(pulled.ok());
  EXPECT_EQ(pulled.status().code(), StatusCode::kResourceExhausted) << pulled.status().to_string();
  const std::string& message = pulled.status().message();
  for (const char* part : {"importing 2 series (", " 161x143x48", " 30x27x48", "needs an estimated 20.6 MB",
                           "memory budget of 4.19 MB", "import fewer series at once, or raise the budget"})
    EXPECT_TRUE(contains(message, part)) << part << " not in: " << message;
  std::printf("refused: %s\n", message.c_str());
  EXPECT_EQ(stored_structures(), 0);
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok()) << info.status().to_string();
  EXPECT_EQ(info->patients(), 0);
  EXPECT_EQ(info->memory_in_use_bytes(), 0);
}

TEST_F(PacsServiceTest, PacsDyingMidwayFailsThePullAndStoresNothing) {
  bool killed = false;
  Result<v1::ImportDicomResponse> pulled = pull_sts([&](const v1::PacsPullProgress& p) {
    if (p.received() == 10 && !killed) {
      pacs_.kill_now();
      killed = true;
    }
    return true;
  });
  ASSERT_TRUE(killed);
  EXPECT_EQ(pulled.status().code(), StatusCode::kUnavailable) << pulled.status().to_string();
  EXPECT_EQ(stored_structures(), 0);
}

TEST_F(PacsServiceTest, ClientCancellingThePullStoresNothing) {
  Result<v1::ImportDicomResponse> pulled = pull_sts([&](const v1::PacsPullProgress& p) { return p.received() < 5; });
  EXPECT_EQ(pulled.status().code(), StatusCode::kCancelled);
  // The server notices at its next instance and drops the folder; poll a while to see it never stores.
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(stored_structures(), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(contains(server_->log(), "code=CANCELLED")) << server_->log();
}

TEST_F(ServiceTest, PacsCallsWithoutAConfiguredPacsNameTheFlag) {
  Result<v1::PacsEchoResponse> r = client_->pacs_echo();
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(r.status().message(), "--pacs")) << r.status().message();
  EXPECT_EQ(client_->pacs_find({}).status().code(), StatusCode::kFailedPrecondition);
}

TEST_F(PacsServiceTest, PacsThatIsDownIsUnavailableNamingIt) {
  pacs_.stop();
  Result<v1::PacsEchoResponse> r = client_->pacs_echo();
  EXPECT_EQ(r.status().code(), StatusCode::kUnavailable);
  EXPECT_TRUE(contains(r.status().message(), "127.0.0.1:" + std::to_string(pacs_.port()))) << r.status().message();
  EXPECT_EQ(pull_sts().status().code(), StatusCode::kUnavailable);
  EXPECT_EQ(stored_structures(), 0);
}

TEST_F(PacsServiceTest, PacsThatRefusesTheAssociationGivesItsReason) {
  start_with_pacs("NOSUCHAE@127.0.0.1:" + std::to_string(pacs_.port()));
  Result<v1::PacsEchoResponse> r = client_->pacs_echo();
  // dcmqrscp rejects with "Called AE Title Not Recognized" (for an unknown calling AE too): the PACS
  // refuses our pair of AE titles, PERMISSION_DENIED (exit 7), keeping the PACS's reason.
  EXPECT_EQ(r.status().code(), StatusCode::kPermissionDenied) << r.status().to_string();
  EXPECT_TRUE(contains(r.status().message(), "NOSUCHAE")) << r.status().message();
  EXPECT_TRUE(contains(r.status().message(), "Called AE Title Not Recognized")) << r.status().message();
  EXPECT_EQ(pull_sts().status().code(), StatusCode::kPermissionDenied);
  EXPECT_EQ(stored_structures(), 0);
}

}  // namespace
}  // namespace soiq::testing

namespace soiq::testing {
namespace {

// A pull of a study whose structure set soiqd stores with another ROI name (imported from a copy
// renamed since): refused as ALREADY_EXISTS naming the object, nothing stored; with replace, the
// PACS's content replaces it.
TEST_F(PacsServiceTest, APullOfObjectsStoredWithOtherContentIsRefusedUnlessReplaced) {
  std::ifstream in(test_data("sts/STS_002/dicom/CT/mask/RS.dcm"), std::ios::binary);
  std::string rs((std::istreambuf_iterator<char>(in)), {});
  for (size_t at = rs.find("GTV_Mass"); at != std::string::npos; at = rs.find("GTV_Mass", at)) rs[at + 4] = 'Z';
  const std::string renamed = dir_.file("RS_renamed.dcm");
  std::ofstream(renamed, std::ios::binary) << rs;
  ASSERT_TRUE(client_->import_dicom({test_data("sts/STS_002/dicom/CT/image"), renamed}).ok());
  const int64_t before = stored_structures();

  Result<v1::ImportDicomResponse> refused = pull_sts();
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kAlreadyExists) << refused.status().to_string();
  EXPECT_TRUE(contains(refused.status().message(), "another name ('GTV_Zass_CT' stored, 'GTV_Mass_CT' sent)"))
      << refused.status().message();
  EXPECT_EQ(stored_structures(), before);

  v1::PacsPullRequest replace;
  replace.add_study_uids(kStsStudyUid);
  replace.set_replace(true);
  Result<v1::ImportDicomResponse> replaced = client_->pacs_pull(replace);
  ASSERT_TRUE(replaced.ok()) << replaced.status().to_string();
  const v1::ImportedStructure* ct = on_modality(*replaced, "CT");
  ASSERT_NE(ct, nullptr);
  EXPECT_EQ(ct->structure().name(), "GTV_Mass_CT");
  EXPECT_TRUE(contains(server_->log(), "event=dicom_replaced structure="));
}

}  // namespace
}  // namespace soiq::testing
