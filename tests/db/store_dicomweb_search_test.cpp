// DICOMweb's searches of the store (search_studies, search_series), on every backend: which
// studies and series match each QIDO-RS condition, their counts and modalities, the order paging
// relies on, and patient names kept and merged.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

// Each case names only the fields it sets (designated initializers); GCC 12's -Wextra still reports
// the others, which take their defaults.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace soiq::db {
namespace {

using testing::new_series;
using testing::new_structure;

// A series imported from DICOM: a SOP class and one SOP instance per slice (dims[2] == 2).
NewSeries dicom_series(const std::string& patient, const std::string& name, const std::string& study,
                       const std::string& date, const std::string& uid, const std::string& modality) {
  NewSeries s = new_series(patient, study, uid, 1.0f);
  s.patient.patient_name = name;
  s.study.study_date = date;
  s.series.modality = modality;
  s.series.frame_of_reference_uid = study + ".9";
  s.series.sop_class_uid = "1.2.840.10008.5.1.4.1.1.2";
  s.series.slice_instance_uids = {uid + ".1", uid + ".2"};
  s.series.series_number = 3;
  s.series.description = "body " + modality;
  return s;
}

// P1 "Doe^John", study 1.1 (2020-01-01): a CT from DICOM, a PT uploaded as a file (no DICOM
// identity), a structure converted on the CT and one uploaded.
// P2 "Smith^Anna Maria", study 2.1 (2021-06-15): an MR from DICOM.
// P3 without a name, study 3.1 without a date: an uploaded structure only.
template <typename Backend>
class StoreDicomwebSearch : public testing::StoreTest<Backend> {
 protected:
  void SetUp() override {
    testing::StoreTest<Backend>::SetUp();
    ImportBatch b;
    b.series.push_back(dicom_series("P1", "Doe^John", "1.1", "20200101", "1.1.1", "CT"));
    b.series.push_back(new_series("P1", "1.1", "1.1.2", 2.0f));
    b.series.back().series.modality = "PT";
    b.structures.push_back(new_structure("P1", "1.1", "GTV", 1.0));
    b.structures.back().source_series_uid = "1.1.1";
    b.structures.back().source_uid = "1.1.77/1";
    b.structures.push_back(new_structure("P1", "1.1", "uploaded", 2.0));
    b.series.push_back(dicom_series("P2", "Smith^Anna Maria", "2.1", "20210615", "2.1.1", "MR"));
    b.structures.push_back(new_structure("P3", "3.1", "lesion", 3.0));
    Result<ImportedBatch> done = this->store_->import_batch(b);
    ASSERT_TRUE(done.ok()) << done.status().to_string();
    gtv_ = done->structures[0].structure.id;
    uploaded_ = done->structures[1].structure.id;
  }

  std::vector<std::string> studies(const StudySearch& s) {
    Result<std::vector<StudyHit>> hits = this->store_->search_studies(s);
    EXPECT_TRUE(hits.ok()) << hits.status().to_string();
    std::vector<std::string> uids;
    if (hits.ok())
      for (const StudyHit& h : *hits) uids.push_back(h.study.study_uid);
    return uids;
  }

  // "series uid" for an image series, "#<structure id>" for a structure's SEG, "#<id>/rt" for its
  // RT Structure Set.
  std::vector<std::string> series(const SeriesSearch& s) {
    Result<std::vector<SeriesHit>> hits = this->store_->search_series(s);
    EXPECT_TRUE(hits.ok()) << hits.status().to_string();
    std::vector<std::string> out;
    if (hits.ok())
      for (const SeriesHit& h : *hits)
        out.push_back(!h.structure ? h.series.series_uid
                                   : "#" + std::to_string(h.structure->id) +
                                         (h.object == StructureObject::kRtStruct ? "/rt" : ""));
    return out;
  }

  int64_t gtv_ = 0, uploaded_ = 0;
};
TYPED_TEST_SUITE(StoreDicomwebSearch, testing::StoreBackends, testing::StoreBackendNames);

using Uids = std::vector<std::string>;

TYPED_TEST(StoreDicomwebSearch, EveryStudyInTheOrderStoredWithItsDicomSeriesCounted) {
  Result<std::vector<StudyHit>> all = this->store_->search_studies({});
  ASSERT_TRUE(all.ok()) << all.status().to_string();
  ASSERT_EQ(all->size(), 3u);
  const StudyHit& a = (*all)[0];
  EXPECT_EQ(a.study.study_uid, "1.1");
  EXPECT_EQ(a.patient.patient_name, "Doe^John");
  EXPECT_EQ(a.modalities, (Uids{"CT", "RTSTRUCT", "SEG"}));  // the uploaded PT is no DICOM series
  EXPECT_EQ(a.series_count, 3);                              // the CT, the GTV's SEG and its RT Structure Set
  EXPECT_EQ(a.instance_count, 4);                            // two slices, one SEG and one RT Structure Set
  EXPECT_EQ(a.study.structure_count, 2);
  const StudyHit& b = (*all)[1];
  EXPECT_EQ(b.study.study_uid, "2.1");
  EXPECT_EQ(b.modalities, (Uids{"MR"}));
  EXPECT_EQ(b.series_count, 1);
  EXPECT_EQ(b.instance_count, 2);
  const StudyHit& c = (*all)[2];
  EXPECT_EQ(c.study.study_uid, "3.1");
  EXPECT_EQ(c.patient.patient_name, "");
  EXPECT_TRUE(c.modalities.empty());
  EXPECT_EQ(c.series_count, 0);
}

TYPED_TEST(StoreDicomwebSearch, StudiesByIdentifiersDatesAndModality) {
  EXPECT_EQ(this->studies({.study_uids = {"3.1", "2.1", "9.9"}}), (Uids{"2.1", "3.1"}));
  EXPECT_EQ(this->studies({.patient_id = "P2"}), (Uids{"2.1"}));
  EXPECT_EQ(this->studies({.patient_id = "P[13]"}), (Uids{"1.1", "3.1"}));
  EXPECT_EQ(this->studies({.study_date_from = "20200101", .study_date_to = "20201231"}), (Uids{"1.1"}));
  EXPECT_EQ(this->studies({.study_date_from = "20210101"}), (Uids{"2.1"}));
  // A study without a date is in no range, open or closed.
  EXPECT_EQ(this->studies({.study_date_to = "20991231"}), (Uids{"1.1", "2.1"}));
  EXPECT_EQ(this->studies({.modality = "CT"}), (Uids{"1.1"}));
  EXPECT_EQ(this->studies({.modality = "SEG"}), (Uids{"1.1"}));
  EXPECT_EQ(this->studies({.modality = "RTSTRUCT"}), (Uids{"1.1"}));
  EXPECT_EQ(this->studies({.modality = "MR"}), (Uids{"2.1"}));
  EXPECT_EQ(this->studies({.modality = "PT"}), (Uids{}));  // uploaded: not a DICOM series
}

TYPED_TEST(StoreDicomwebSearch, NamesByPatternAndByWordsIgnoringCase) {
  EXPECT_EQ(this->studies({.patient_name_glob = "DOE*"}), (Uids{"1.1"}));
  EXPECT_EQ(this->studies({.patient_name_glob = "*anna*"}), (Uids{"2.1"}));
  EXPECT_EQ(this->studies({.patient_name_glob = "doe"}), (Uids{}));  // a pattern matches the whole name
  // Fuzzy: each word starts a component (after ^) or a word (after a space).
  EXPECT_EQ(this->studies({.patient_name_words = {"ann"}}), (Uids{"2.1"}));
  EXPECT_EQ(this->studies({.patient_name_words = {"MAR"}}), (Uids{"2.1"}));
  EXPECT_EQ(this->studies({.patient_name_words = {"smi", "jo"}}), (Uids{}));
  EXPECT_EQ(this->studies({.patient_name_words = {"jo", "do"}}), (Uids{"1.1"}));
  EXPECT_EQ(this->studies({.patient_name_words = {"ohn"}}), (Uids{}));  // inside a word
  // Glob characters in a word are literal.
  EXPECT_EQ(this->studies({.patient_name_words = {"*"}}), (Uids{}));
}

TYPED_TEST(StoreDicomwebSearch, OffsetAndLimitPageTheSameOrder) {
  EXPECT_EQ(this->studies({.offset = 0, .limit = 2}), (Uids{"1.1", "2.1"}));
  EXPECT_EQ(this->studies({.offset = 2, .limit = 2}), (Uids{"3.1"}));
  EXPECT_EQ(this->studies({.offset = 3, .limit = 2}), (Uids{}));
  EXPECT_EQ(this->series({.offset = 1, .limit = 1}), (Uids{"#" + std::to_string(this->gtv_)}));
  // A structure's two series may fall on two pages.
  EXPECT_EQ(this->series({.offset = 2, .limit = 2}), (Uids{"#" + std::to_string(this->gtv_) + "/rt", "2.1.1"}));
}

TYPED_TEST(StoreDicomwebSearch, SeriesAreImagesFromDicomThenStructureSegsAndRtStructureSets) {
  const std::string gtv = "#" + std::to_string(this->gtv_);
  const std::string gtv_rt = gtv + "/rt";
  EXPECT_EQ(this->series({}), (Uids{"1.1.1", gtv, gtv_rt, "2.1.1"}));
  EXPECT_EQ(this->series({.study_uids = {"2.1"}}), (Uids{"2.1.1"}));
  EXPECT_EQ(this->series({.patient_id = "P1"}), (Uids{"1.1.1", gtv, gtv_rt}));
  EXPECT_EQ(this->series({.modality = "SEG"}), (Uids{gtv}));
  EXPECT_EQ(this->series({.modality = "RTSTRUCT"}), (Uids{gtv_rt}));
  EXPECT_EQ(this->series({.modality = "CT"}), (Uids{"1.1.1"}));
  EXPECT_EQ(this->series({.series_uid = "1.1.1"}), (Uids{"1.1.1"}));
  EXPECT_EQ(this->series({.series_uid = "1.1.2"}), (Uids{}));  // uploaded, no DICOM identity
  EXPECT_EQ(this->series({.structure_id = this->gtv_}), (Uids{gtv, gtv_rt}));
  EXPECT_EQ(this->series({.structure_id = this->gtv_, .object = StructureObject::kRtStruct}), (Uids{gtv_rt}));
  EXPECT_EQ(this->series({.object = StructureObject::kSeg}), (Uids{gtv}));
  EXPECT_EQ(this->series({.object = StructureObject::kSeg, .modality = "RTSTRUCT"}), (Uids{}));
  EXPECT_EQ(this->series({.object = StructureObject::kSeg, .modality = "CT"}), (Uids{}));
  EXPECT_EQ(this->series({.structure_id = this->uploaded_}), (Uids{}));

  Result<std::vector<SeriesHit>> seg = this->store_->search_series({.structure_id = this->gtv_});
  ASSERT_TRUE(seg.ok());
  ASSERT_EQ(seg->size(), 2u);
  EXPECT_EQ((*seg)[0].object, StructureObject::kSeg);
  EXPECT_EQ((*seg)[1].object, StructureObject::kRtStruct);
  EXPECT_EQ((*seg)[1].structure->name, "GTV");
  const SeriesHit& h = (*seg)[0];
  EXPECT_EQ(h.structure->name, "GTV");
  EXPECT_EQ(h.series.series_uid, "1.1.1");  // converted on the CT
  EXPECT_EQ(h.series.slice_instance_uids, (Uids{"1.1.1.1", "1.1.1.2"}));
  EXPECT_EQ(h.series.series_number, 3);
  EXPECT_EQ(h.series.description, "body CT");
  EXPECT_EQ(h.study.study_date, "20200101");
  EXPECT_EQ(h.patient.patient_name, "Doe^John");
}

TYPED_TEST(StoreDicomwebSearch, ABadSearchIsInvalidArgument) {
  for (const StudySearch& s : {StudySearch{.limit = 0}, StudySearch{.limit = kMaxSearchLimit + 1},
                               StudySearch{.offset = -1}, StudySearch{.study_date_from = "2020"}}) {
    Result<std::vector<StudyHit>> r = this->store_->search_studies(s);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  }
  Result<std::vector<SeriesHit>> r = this->store_->search_series({.limit = 0});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
}

TYPED_TEST(StoreDicomwebSearch, ANameIsKeptWhenALaterImportHasNone) {
  NewSeries again = dicom_series("P1", "", "1.1", "20200101", "1.1.3", "CT");
  ASSERT_TRUE(this->store_->put_series(again).ok());
  Result<PatientRecord> p = this->store_->get_patient("P1");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->patient_name, "Doe^John");
  again = dicom_series("P1", "Doe^Johnny", "1.1", "20200101", "1.1.3", "CT");
  ASSERT_TRUE(this->store_->put_series(again).ok());
  EXPECT_EQ(this->store_->get_patient("P1")->patient_name, "Doe^Johnny");
  // Not UTF-8: refused, the name not quoted in the message.
  again.patient.patient_name = "D\xE9j\xE0";
  Result<bool> bad = this->store_->put_series(again);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(bad.status().message().find("D\xE9"), std::string::npos);
}

}  // namespace
}  // namespace soiq::db
