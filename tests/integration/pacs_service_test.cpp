// DICOM out and the PACS through a real soiqd (soiqd --pacs) against a real PACS on loopback,
// DCMTK's dcmqrscp loaded with DCMTK's storescu (tests/dicom/dcmqrscp_process.h): echo, find with
// wildcards and date ranges, pull into soiq and query what came, a SEG exported and pushed back and
// found on the PACS again, and the failures: no PACS configured, a PACS that is down, one that
// refuses our association, one that dies midway, a client that cancels. Each test has its own
// PACS and its own soiqd, so none sees another's pushes.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "core/base/run_length_volume.h"
#include "core/geometry/primitives.h"
#include "core/io/read_image.h"
#include "dicom/pacs_pull.h"
#include "dicom/read_seg.h"
#include "tests/support/dcmqrscp_process.h"
#include "tests/integration/service_fixture.h"
#include "tests/integration/sts_query.h"

namespace soiq::testing {
namespace {

using dicom::testing::DcmqrscpProcess;

constexpr const char* kStsStudyUid = "1.3.6.1.4.1.14519.5.2.1.5168.1900.190311276211389538203367070477";
constexpr int kStsFiles = 98;  // 48 CT + 48 PET slices + 2 RT Structure Sets

std::string data(const std::string& relative) { return std::string(SOIQ_TEST_DATA_DIR) + "/" + relative; }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class PacsServiceTest : public ServiceTest {
 protected:
  void SetUp() override {
    const std::string error = pacs_.start();
    if (error.rfind("not installed", 0) == 0) GTEST_SKIP() << error;
    ASSERT_EQ(error, "");
    ASSERT_EQ(pacs_.load({data("sts/STS_002/dicom"), data("dicom/CT_small.dcm")}), "");
    start_with_pacs(pacs_address());
  }

  std::string pacs_address() const {
    return std::string(DcmqrscpProcess::kAeTitle) + "@127.0.0.1:" + std::to_string(pacs_.port());
  }

  void start_with_pacs(const std::string& address, const std::vector<std::string>& more = {}) {
    std::vector<std::string> args = {"--pacs-timeout", "5"};
    if (!address.empty()) args.insert(args.end(), {"--pacs", address});
    args.insert(args.end(), more.begin(), more.end());
    start(args);
    client_ = std::make_unique<client::Client>(connect());
  }

  // The structure imported on the CT series of a pull or import.
  static const v1::ImportedStructure* on_modality(const v1::ImportDicomResponse& r, const std::string& modality) {
    for (const v1::Series& s : r.series()) {
      if (s.modality() != modality) continue;
      for (const v1::ImportedStructure& i : r.structures())
        if (i.referenced_series_uid() == s.series_uid()) return &i;
    }
    return nullptr;
  }

  Result<v1::ImportDicomResponse> pull_sts(const std::function<bool(const v1::PacsPullProgress&)>& progress = {}) {
    v1::PacsPullRequest r;
    r.add_study_uids(kStsStudyUid);
    return client_->pacs_pull(r, progress);
  }

  int64_t stored_structures() {
    Result<v1::ServerInfo> info = client_->server_info();
    EXPECT_TRUE(info.ok());
    return info.ok() ? info->structures() + info->series() : -1;
  }

  DcmqrscpProcess pacs_;
};

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
  Result<v1::ImportDicomResponse> direct = direct_client->import_dicom({data("sts/STS_002/dicom")});
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
// 12 bytes per voxel plus one slice at 4 bytes per pixel each, 13,823,140 bytes.
TEST_F(PacsServiceTest, PullThatCanNeverFitTheMemoryBudgetIsRefusedAndStoresNothing) {
  start_with_pacs(pacs_address(), {"--memory-budget", "4M"});
  Result<v1::ImportDicomResponse> pulled = pull_sts();
  ASSERT_FALSE(pulled.ok());
  EXPECT_EQ(pulled.status().code(), StatusCode::kResourceExhausted) << pulled.status().to_string();
  const std::string& message = pulled.status().message();
  for (const char* part : {"importing 2 series (", " 161x143x48", " 30x27x48", "needs an estimated 13.8 MB",
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

TEST_F(PacsServiceTest, ExportedSegHoldsExactlyTheShippedMaskAndPushedItIsFoundAgain) {
  Result<v1::ImportDicomResponse> pulled = pull_sts();
  ASSERT_TRUE(pulled.ok()) << pulled.status().to_string();
  const v1::ImportedStructure* ct = on_modality(*pulled, "CT");
  ASSERT_NE(ct, nullptr);

  // Export: the SEG read back by DCMTK is the NIfTI mask shipped with the data, voxel for voxel.
  Result<Image> mask_image = read_image(data("sts/STS_002/CT_mask.nii.gz"));
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
