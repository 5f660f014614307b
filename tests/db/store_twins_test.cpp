// Store::stage1 with twins, on every backend: each candidate's contralateral twin comes from the
// same query, checked against a brute-force search over the stored structures of a random store.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_structure;

std::string ascii_lower_copy(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return c < 128 ? std::tolower(c) : c; });
  return s;
}

// The twin as the query engine defined it before SQL did: the first structure of the study, by id,
// with the same lower-case name and the other side.
std::optional<int64_t> brute_twin(const StructureRecord& s, const std::vector<StructureRecord>& all) {
  if (s.laterality != "L" && s.laterality != "R") return std::nullopt;
  const std::string other = s.laterality == "L" ? "R" : "L";
  for (const StructureRecord& t : all)
    if (t.study_uid == s.study_uid && t.laterality == other && ascii_lower_copy(t.name) == ascii_lower_copy(s.name))
      return t.id;
  return std::nullopt;
}

template <typename Backend>
class StoreTwins : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreTwins, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreTwins, EveryCandidatesTwinIsTheBruteForceOne) {
  Store* store = this->store_.get();
  std::mt19937 rng(7);
  const char* names[] = {"Hippocampus", "hippocampus", "HIPPOCAMPUS", "amygdala", "Amygdala", "insula"};
  const char* sides[] = {"L", "R", ""};
  for (int i = 0; i < 120; ++i) {
    NewStructure s = new_structure("P" + std::to_string(rng() % 4), "", names[rng() % 6], double(i));
    s.study.study_uid = "S" + s.patient.patient_id + "." + std::to_string(rng() % 3);
    s.laterality = sides[rng() % 3];
    ASSERT_TRUE(store->add_structure(s).ok());
  }
  Stage1Filter all_filter;
  Result<std::vector<Candidate>> every = store->stage1(all_filter, 1000);
  ASSERT_TRUE(every.ok());
  std::vector<StructureRecord> all;
  for (const Candidate& c : *every) {
    EXPECT_FALSE(c.twin) << "no twin without Stage1Filter::twins";
    all.push_back(c.structure);
  }

  Stage1Filter f;
  f.twins = true;
  f.laterality = "L";  // stage 1 keeps only left sides; their twins are right sides
  Result<std::vector<Candidate>> left = store->stage1(f, 1000);
  ASSERT_TRUE(left.ok()) << left.status().to_string();
  int with_twin = 0;
  for (const Candidate& c : *left) {
    const std::optional<int64_t> expected = brute_twin(c.structure, all);
    ASSERT_EQ(c.twin.has_value(), expected.has_value()) << c.structure.id;
    if (!expected) continue;
    ++with_twin;
    EXPECT_EQ(c.twin->id, *expected);
    EXPECT_EQ(c.twin->laterality, "R");
    EXPECT_EQ(c.twin->study_uid, c.structure.study_uid);
  }
  EXPECT_GT(with_twin, 5);  // the random store must exercise the join
  EXPECT_LT(with_twin, int(left->size()));
}

TYPED_TEST(StoreTwins, AStructureWithoutLateralityHasNoTwin) {
  Store* store = this->store_.get();
  NewStructure a = new_structure("P", "S", "insula", 1);
  NewStructure b = new_structure("P", "S", "insula", 2);
  b.laterality = "L";
  ASSERT_TRUE(store->add_structure(a).ok());
  ASSERT_TRUE(store->add_structure(b).ok());
  Stage1Filter f;
  f.twins = true;
  Result<std::vector<Candidate>> r = store->stage1(f, 10);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->size(), 2u);
  EXPECT_FALSE((*r)[0].twin);
  EXPECT_FALSE((*r)[1].twin);
}

}  // namespace
}  // namespace soiq::db
