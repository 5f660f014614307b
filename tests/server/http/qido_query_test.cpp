// QIDO-RS query parameters -> store searches (server/http/qido_query.h): each matching rule of
// PS3.4 C.2.2.2 soiq implements, and each refusal naming what to do instead.
#include "server/http/qido_query.h"

#include <gtest/gtest.h>

#include "server/app/structure_object_uids.h"

namespace soiq::server::http {
namespace {

Result<QidoQuery> studies(const QueryParams& p, bool names = true) {
  return parse_qido(QidoLevel::kStudy, "", "", p, names);
}

std::string refusal(const Result<QidoQuery>& q) {
  EXPECT_FALSE(q.ok());
  EXPECT_EQ(q.status().code(), StatusCode::kInvalidArgument);
  return q.status().message();
}

TEST(QidoQuery, KeysByKeywordOrTagBecomeTheStudySearch) {
  Result<QidoQuery> q = studies({{"PatientID", "AB*"},
                                 {"00080020", "20200101-20201231"},
                                 {"ModalitiesInStudy", "CT"},
                                 {"StudyInstanceUID", "1.2,1.3\\1.4"},
                                 {"AccessionNumber", "A1"},
                                 {"limit", "10"},
                                 {"offset", "20"}});
  ASSERT_TRUE(q.ok()) << q.status().to_string();
  EXPECT_EQ(q->studies.patient_id, "AB*");
  EXPECT_EQ(q->studies.study_date_from, "20200101");
  EXPECT_EQ(q->studies.study_date_to, "20201231");
  EXPECT_EQ(q->studies.modality, "CT");
  EXPECT_EQ(q->studies.study_uids, (std::vector<std::string>{"1.2", "1.3", "1.4"}));
  EXPECT_EQ(q->studies.accession_number, "A1");
  EXPECT_EQ(q->studies.limit, 10);
  EXPECT_EQ(q->studies.offset, 20);
}

TEST(QidoQuery, DatesSingleOrOpenRanges) {
  EXPECT_EQ(studies({{"StudyDate", "20200101"}})->studies.study_date_to, "20200101");
  EXPECT_EQ(studies({{"StudyDate", "-20200101"}})->studies.study_date_from, "");
  EXPECT_EQ(studies({{"StudyDate", "20200101-"}})->studies.study_date_to, "");
  for (const char* bad : {"2020", "20201301", "20200101-2021", "-", "1-2-3"})
    EXPECT_NE(refusal(studies({{"StudyDate", bad}})).find("StudyDate"), std::string::npos) << bad;
}

TEST(QidoQuery, WildcardsAreGlobsWithBracketsLiteral) {
  EXPECT_EQ(dicom_wildcards_to_glob("A[1]*?"), "A[[]1]*?");
  EXPECT_EQ(studies({{"PatientID", "X[Y"}})->studies.patient_id, "X[[]Y");
  // "*" alone matches everything: no condition.
  EXPECT_EQ(studies({{"PatientID", "*"}})->studies.patient_id, "");
  EXPECT_NE(refusal(studies({{"AccessionNumber", "A*"}})).find("exact"), std::string::npos);
  EXPECT_NE(refusal(studies({{"ModalitiesInStudy", "CT,MR"}})).find("one value"), std::string::npos);
}

TEST(QidoQuery, NamesByPatternOrFuzzyWordsAndOnlyWhenKept) {
  EXPECT_EQ(studies({{"PatientName", "Doe*"}})->studies.patient_name_glob, "Doe*");
  Result<QidoQuery> fuzzy = studies({{"PatientName", "doe^jo*"}, {"fuzzymatching", "true"}});
  ASSERT_TRUE(fuzzy.ok());
  EXPECT_EQ(fuzzy->studies.patient_name_words, (std::vector<std::string>{"doe", "jo"}));
  EXPECT_EQ(fuzzy->studies.patient_name_glob, "");
  EXPECT_NE(refusal(studies({{"PatientName", "Doe"}}, false)).find("--keep-patient-names"), std::string::npos);
  EXPECT_NE(refusal(studies({{"fuzzymatching", "1"}})).find("true or false"), std::string::npos);
}

TEST(QidoQuery, IncludefieldAndReturnKeysAddAttributes) {
  Result<QidoQuery> q =
      studies({{"includefield", "PatientAge,00081030"}, {"includefield", "NoSuchThing"}, {"StudyDescription", ""}});
  ASSERT_TRUE(q.ok()) << q.status().to_string();
  EXPECT_EQ(q->include, (std::set<uint32_t>{tags::kPatientAge, tags::kStudyDescription}));
  EXPECT_FALSE(q->include_all);
  EXPECT_TRUE(studies({{"includefield", "all"}})->include_all);
}

TEST(QidoQuery, LimitIsClampedOffsetAndKeysChecked) {
  Result<QidoQuery> big = studies({{"limit", "100000"}});
  ASSERT_TRUE(big.ok());
  EXPECT_EQ(big->limit, db::kMaxSearchLimit);
  EXPECT_TRUE(big->limit_clamped);
  EXPECT_EQ(studies({})->limit, db::kMaxSearchLimit);
  for (const QueryParams& bad : std::vector<QueryParams>{
           {{"limit", "0"}}, {{"limit", "ten"}}, {{"offset", "-1"}}, {{"PatientID", "a"}, {"PatientID", "b"}}})
    refusal(studies(bad));
  const std::string unknown = refusal(studies({{"Frobnicate", "1"}}));
  EXPECT_NE(unknown.find("PatientID"), std::string::npos) << unknown;  // says what it takes
  // Known, but not matched at this level: refused, pointing at includefield.
  EXPECT_NE(refusal(studies({{"StudyDescription", "x"}})).find("includefield"), std::string::npos);
  EXPECT_NE(refusal(studies({{"Modality", "CT"}})).find("ModalitiesInStudy"), std::string::npos);
}

TEST(QidoQuery, SeriesAndInstancesBelowAPath) {
  Result<QidoQuery> q = parse_qido(QidoLevel::kSeries, "1.2", "", {{"Modality", "SEG"}}, false);
  ASSERT_TRUE(q.ok());
  EXPECT_EQ(q->series.study_uids, std::vector<std::string>{"1.2"});
  EXPECT_EQ(q->series.modality, "SEG");
  // A StudyInstanceUID key naming another study than the path: nothing matches.
  EXPECT_TRUE(parse_qido(QidoLevel::kSeries, "1.2", "", {{"StudyInstanceUID", "1.3"}}, false)->matches_nothing);
  // An image series by UID; a SEG or RT Structure Set series by the structure id and object its
  // UID carries.
  EXPECT_EQ(parse_qido(QidoLevel::kInstance, "1.2", "1.2.3", {}, false)->series.series_uid, "1.2.3");
  db::StructureRecord s;
  s.id = 42;
  s.surface.sha256 = std::string(64, 'a');
  const std::string seg = structure_object_uids(s, db::StructureObject::kSeg).series_uid;
  Result<QidoQuery> by_seg = parse_qido(QidoLevel::kInstance, "1.2", seg, {{"SOPInstanceUID", "9.9"}}, false);
  ASSERT_TRUE(by_seg.ok());
  EXPECT_EQ(by_seg->series.structure_id, 42);
  EXPECT_EQ(by_seg->series.series_uid, "");
  EXPECT_EQ(by_seg->series_uid_asked, seg);
  EXPECT_EQ(by_seg->sop_instance_uid, "9.9");
  EXPECT_EQ(by_seg->series.object, db::StructureObject::kSeg);
  const std::string rt = structure_object_uids(s, db::StructureObject::kRtStruct).series_uid;
  Result<QidoQuery> by_rt = parse_qido(QidoLevel::kSeries, "1.2", rt, {}, false);
  ASSERT_TRUE(by_rt.ok());
  EXPECT_EQ(by_rt->series.structure_id, 42);
  EXPECT_EQ(by_rt->series.object, db::StructureObject::kRtStruct);
  EXPECT_EQ(by_rt->series_uid_asked, rt);
  refusal(parse_qido(QidoLevel::kSeries, "", "", {{"SOPInstanceUID", "1"}}, false));
}

}  // namespace
}  // namespace soiq::server::http
