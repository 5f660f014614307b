// A study's DICOM Study Time, Study ID and Accession Number (for the SEGs soiq exports on it), on
// every backend: kept across updates that do not give them, refused when malformed.
#include <gtest/gtest.h>

#include <string>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_series;
using testing::new_structure;
using testing::series_of_identified_study;

template <typename Backend>
class StoreStudyIdentity : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreStudyIdentity, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreStudyIdentity, StudyTimeIdAndAccessionNumberRoundTrip) {
  Store* store = this->store_.get();
  ASSERT_TRUE(store->put_series(series_of_identified_study()).ok());
  auto study = store->get_study("1.2.3");
  ASSERT_TRUE(study.ok()) << study.status().to_string();
  EXPECT_EQ(study->study_time, "101512.5");
  EXPECT_EQ(study->study_id, "S-17");
  EXPECT_EQ(study->accession_number, "ACC0042");
  auto listed = store->list_studies("P1", {});
  ASSERT_TRUE(listed.ok());
  ASSERT_EQ(listed->items.size(), 1u);
  EXPECT_EQ(listed->items[0].accession_number, "ACC0042");
}

TYPED_TEST(StoreStudyIdentity, AWriteWithoutThemKeepsTheStoredValues) {
  Store* store = this->store_.get();
  ASSERT_TRUE(store->put_series(series_of_identified_study()).ok());
  // An upload into the same study knows nothing of its DICOM identity.
  ASSERT_TRUE(store->add_structure(new_structure("P1", "1.2.3", "GTV", 0)).ok());
  auto study = store->get_study("1.2.3");
  ASSERT_TRUE(study.ok());
  EXPECT_EQ(study->study_time, "101512.5");
  EXPECT_EQ(study->study_id, "S-17");
  EXPECT_EQ(study->accession_number, "ACC0042");
}

TYPED_TEST(StoreStudyIdentity, AccessionNumberWithAControlCharacterIsRefusedNamingTheField) {
  Store* store = this->store_.get();
  NewSeries s = series_of_identified_study();
  s.study.accession_number = "ACC\n42";
  auto r = store->put_series(s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("accession number"), std::string::npos) << r.status().message();
  EXPECT_EQ(store->counts()->studies, 0);
}

}  // namespace
}  // namespace soiq::db
