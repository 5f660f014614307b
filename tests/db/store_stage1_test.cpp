// Store::stage1 and the paged lists against a brute-force evaluation in C++ over a random store
// (stage1_random_store.h), on every backend: every filter alone, then random combinations.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "db/store.h"
#include "tests/db/stage1_oracle.h"
#include "tests/db/stage1_random_store.h"
#include "tests/db/store_backends.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::glob_match;
using testing::Row;
using testing::single_filters;

template <typename Backend>
class Stage1 : public testing::Stage1Store<Backend> {};
TYPED_TEST_SUITE(Stage1, testing::StoreBackends, testing::StoreBackendNames);

TEST(GlobOracle, AgreesWithSqliteOnHandCases) {
  EXPECT_TRUE(glob_match("a*c", "abbc"));
  EXPECT_TRUE(glob_match("*", ""));
  EXPECT_FALSE(glob_match("?", ""));
  EXPECT_TRUE(glob_match("[^a]x", "bx"));
  EXPECT_FALSE(glob_match("[^a]x", "ax"));
  EXPECT_TRUE(glob_match("*[[]FDG]", "PET/CT [FDG]"));
  EXPECT_TRUE(glob_match("Q00[0-4]*", "Q0031"));
  EXPECT_FALSE(glob_match("Q00[0-4]*", "Q0051"));
}

TYPED_TEST(Stage1, EveryFilterAloneMatchesTheBruteForce) {
  this->expect_same(Stage1Filter{}, "no filter");
  for (const auto& [label, set] : single_filters()) {
    Stage1Filter f;
    set(f);
    this->expect_same(f, label);
  }
}

TYPED_TEST(Stage1, RandomCombinationsMatchTheBruteForce) {
  const auto filters = single_filters();
  std::mt19937_64 rng(99);
  int nonempty = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Stage1Filter f;
    std::string label;
    const int n = 2 + int(rng() % 3);
    for (int i = 0; i < n; ++i) {
      const auto& [name, set] = filters[rng() % filters.size()];
      set(f);
      label += name + "; ";
    }
    if (f.min_age_years && f.max_age_years && *f.min_age_years > *f.max_age_years) continue;
    nonempty += !this->expected_ids(f).empty();
    this->expect_same(f, label);
  }
  EXPECT_GT(nonempty, 50) << "the combinations should not be mostly empty, or they prove little";
}

TYPED_TEST(Stage1, CandidatesCarryThePatientAndStudy) {
  auto got = this->store_->stage1(Stage1Filter{}, 1'000'000);
  ASSERT_TRUE(got.ok());
  ASSERT_EQ(got->size(), this->rows_->size());
  for (size_t i = 0; i < this->rows_->size(); ++i) {
    const Candidate& c = (*got)[i];
    const Row& r = (*this->rows_)[i];
    EXPECT_EQ(c.patient.patient_id, r.patient.patient_id);
    EXPECT_EQ(c.patient.sex, r.patient.sex);
    EXPECT_EQ(c.patient.birth_date, r.patient.birth_date);
    EXPECT_GE(c.patient.structure_count, 1);
    EXPECT_EQ(c.study.study_uid, r.study.study_uid);
    EXPECT_EQ(c.study.study_date, r.study.study_date);
    EXPECT_EQ(c.study.description, r.study.description);
    EXPECT_EQ(c.study.age_years, r.study.age_years);
    EXPECT_GE(c.study.structure_count, 1);
    EXPECT_EQ(c.structure.name, r.name);
    EXPECT_EQ(c.structure.laterality, r.laterality);
    EXPECT_EQ(c.structure.study_uid, r.study.study_uid);
  }
}

TYPED_TEST(Stage1, MoreThanTheLimitIsResourceExhaustedWithTheCount) {
  Stage1Filter f;
  f.structure_name_glob = "hippo*";
  const size_t n = this->expected_ids(f).size();
  ASSERT_GT(n, 5u);
  auto got = this->store_->stage1(f, 5);
  ASSERT_FALSE(got.ok());
  EXPECT_EQ(got.status().code(), StatusCode::kResourceExhausted);
  EXPECT_TRUE(contains(got.status().message(), std::string("matches ") + std::to_string(n) + " structures"))
      << got.status().message();
  EXPECT_TRUE(contains(got.status().message(), "narrow")) << got.status().message();
  EXPECT_TRUE(this->store_->stage1(f, int64_t(n)).ok());
}

TYPED_TEST(Stage1, BadFilterIsInvalidArgument) {
  Stage1Filter f;
  f.study_date_from = "2020";
  EXPECT_EQ(this->store_->stage1(f, 10).status().code(), StatusCode::kInvalidArgument);
  Stage1Filter g;
  g.min_age_years = 60.0;
  g.max_age_years = 50.0;
  EXPECT_EQ(this->store_->stage1(g, 10).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(this->store_->stage1(Stage1Filter{}, 0).status().code(), StatusCode::kInvalidArgument);
}

TYPED_TEST(Stage1, StructurePagesCoverEveryRowExactlyOnce) {
  for (const std::string& glob : {std::string(), std::string("*HIPPO*")}) {
    StructureFilter f;
    f.name_glob = glob;
    std::vector<int64_t> seen;
    PageRequest page{7, ""};
    int pages = 0;
    do {
      auto got = this->store_->list_structures(f, page);
      ASSERT_TRUE(got.ok()) << got.status().to_string();
      ASSERT_LE(got->items.size(), 7u);
      for (const auto& s : got->items) seen.push_back(s.id);
      page.page_token = got->next_page_token;
      ++pages;
    } while (!page.page_token.empty() && pages < 10000);
    Stage1Filter same;
    same.structure_name_glob = glob;
    EXPECT_EQ(seen, this->expected_ids(same)) << "glob '" << glob << "'";
  }
}

// `soiq ls structures --patient 'P00*'`: a patient id with a wildcard is a glob, as in stage 1;
// without one it is exact (an id may hold no wildcard, so nothing exact is lost).
TYPED_TEST(Stage1, StructuresOfPatientsMatchingAGlobAreThoseStage1Finds) {
  for (const std::string& glob : {std::string("P00*"), std::string("Q?0*"), std::string("P0000")}) {
    StructureFilter f;
    f.patient_id = glob;
    std::vector<int64_t> seen;
    PageRequest page{50, ""};
    do {
      auto got = this->store_->list_structures(f, page);
      ASSERT_TRUE(got.ok()) << got.status().to_string();
      for (const auto& s : got->items) seen.push_back(s.id);
      page.page_token = got->next_page_token;
    } while (!page.page_token.empty());
    Stage1Filter same;
    same.patient_id_glob = glob;
    EXPECT_FALSE(seen.empty()) << glob;
    EXPECT_EQ(seen, this->expected_ids(same)) << glob;
  }
}

TYPED_TEST(Stage1, PatientAndStudyPagesCoverEveryRowExactlyOnce) {
  std::set<std::string> patients;
  std::vector<std::string> order;
  PageRequest page{9, ""};
  do {
    auto got = this->store_->list_patients(PatientFilter{}, page);
    ASSERT_TRUE(got.ok());
    for (const auto& p : got->items) order.push_back(p.patient_id);
    page.page_token = got->next_page_token;
  } while (!page.page_token.empty());
  patients.insert(order.begin(), order.end());
  EXPECT_EQ(patients.size(), order.size());  // no repeats
  EXPECT_EQ(patients, *this->patients_);
  EXPECT_TRUE(std::is_sorted(order.begin(), order.end()));

  auto one = this->store_->list_patients(PatientFilter{"Q*", "F"}, PageRequest{0, ""});
  ASSERT_TRUE(one.ok());
  for (const auto& p : one->items) EXPECT_TRUE(p.patient_id[0] == 'Q' && p.sex == "F");

  auto studies = this->store_->list_studies("P0000", PageRequest{1, ""});
  ASSERT_TRUE(studies.ok());
  std::set<std::string> seen;
  PageRequest sp{1, ""};
  do {
    auto got = this->store_->list_studies("P0000", sp);
    ASSERT_TRUE(got.ok());
    for (const auto& s : got->items) EXPECT_TRUE(seen.insert(s.study_uid).second);
    sp.page_token = got->next_page_token;
  } while (!sp.page_token.empty());
  EXPECT_EQ(int64_t(seen.size()), this->store_->get_patient("P0000")->study_count);
}

TYPED_TEST(Stage1, TokenOfAnotherListIsInvalidArgument) {
  auto first = this->store_->list_patients(PatientFilter{}, PageRequest{2, ""});
  ASSERT_FALSE(first->next_page_token.empty());
  auto wrong = this->store_->list_structures(StructureFilter{}, PageRequest{2, first->next_page_token});
  EXPECT_EQ(wrong.status().code(), StatusCode::kInvalidArgument);
  auto garbage = this->store_->list_patients(PatientFilter{}, PageRequest{2, "not-a-token"});
  EXPECT_EQ(garbage.status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq::db
