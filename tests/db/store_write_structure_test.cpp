// Store writes of structures, on every backend: add_structure's record, the rows it creates or
// updates, and the inputs it refuses without leaving anything behind.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "db/store.h"
#include "db/surface_blob.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_structure;

template <typename Backend>
class StoreWriteStructure : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreWriteStructure, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreWriteStructure, AddStructureReturnsTheFullRecord) {
  NewStructure s = new_structure("P1", "1.2.3", "Hippocampus", 2.0);
  s.patient.sex = "F";
  s.patient.birth_date = "19600101";
  s.study.study_date = "20200101";
  s.study.modality = "MR";
  s.laterality = "L";
  s.robust = true;
  auto added = this->store_->add_structure(s);
  ASSERT_TRUE(added.ok()) << added.status().to_string();
  const StructureRecord& r = added->structure;
  EXPECT_GT(r.id, 0);
  EXPECT_EQ(r.patient_id, "P1");
  EXPECT_EQ(r.study_uid, "1.2.3");
  EXPECT_EQ(r.name, "Hippocampus");
  EXPECT_EQ(r.laterality, "L");
  EXPECT_TRUE(r.robust);
  EXPECT_EQ(r.surface.sha256, s.surface.sha256);
  EXPECT_EQ(r.surface.vertex_count, 4);
  EXPECT_EQ(r.surface.triangle_count, 4);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(r.surface.bounds_mm[i], s.surface.bounds_mm[i]);
  // ISO 8601 UTC: 2024-01-02T03:04:05.678Z
  ASSERT_EQ(r.created_at.size(), 24u) << r.created_at;
  EXPECT_EQ(r.created_at[10], 'T');
  EXPECT_EQ(r.created_at.back(), 'Z');
  EXPECT_FALSE(added->surface_already_stored);

  auto study = this->store_->get_study("1.2.3");
  ASSERT_TRUE(study.ok());
  ASSERT_TRUE(study->age_years.has_value());
  EXPECT_EQ(*study->age_years, 60.0);
  EXPECT_EQ(study->structure_count, 1);
  auto patient = this->store_->get_patient("P1");
  EXPECT_EQ(patient->sex, "F");
  EXPECT_EQ(patient->study_count, 1);
  EXPECT_EQ(patient->structure_count, 1);
}

TYPED_TEST(StoreWriteStructure, SameMeshTwiceIsStoredOnceForTwoStructures) {
  auto a = this->store_->add_structure(new_structure("P1", "S1", "left"));
  auto b = this->store_->add_structure(new_structure("P2", "S2", "right"));
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_FALSE(a->surface_already_stored);
  EXPECT_TRUE(b->surface_already_stored);
  EXPECT_EQ(a->structure.surface.sha256, b->structure.surface.sha256);
  EXPECT_NE(a->structure.id, b->structure.id);
  EXPECT_EQ(this->counts().surfaces, 1);
  EXPECT_EQ(this->counts().structures, 2);
  auto blob = this->store_->get_surface_blob(a->structure.surface.sha256);
  ASSERT_TRUE(blob.ok());
  auto mesh = decode_surface(*blob);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->vertices_mm, testing::tetrahedron(0).vertices_mm);
}

TYPED_TEST(StoreWriteStructure, NonEmptyFieldsOverwriteAndEmptyOnesKeep) {
  NewStructure s = new_structure("P1", "S1", "a");
  s.patient.sex = "M";
  s.study.description = "first";
  ASSERT_TRUE(this->store_->add_structure(s).ok());
  NewStructure t = new_structure("P1", "S1", "b");
  t.patient.birth_date = "19700101";
  t.study.modality = "CT";
  ASSERT_TRUE(this->store_->add_structure(t).ok());
  auto p = this->store_->get_patient("P1");
  EXPECT_EQ(p->sex, "M");
  EXPECT_EQ(p->birth_date, "19700101");
  auto st = this->store_->get_study("S1");
  EXPECT_EQ(st->description, "first");
  EXPECT_EQ(st->modality, "CT");
}

TYPED_TEST(StoreWriteStructure, StudyOfAnotherPatientIsRefusedAndLeavesNothing) {
  ASSERT_TRUE(this->store_->add_structure(new_structure("P1", "S1", "a")).ok());
  const Counts before = this->counts();
  auto bad = this->store_->add_structure(new_structure("P2", "S1", "b", 5.0));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(bad.status().message(), "study 'S1' belongs to patient 'P1', not to 'P2'"))
      << bad.status().message();
  EXPECT_EQ(this->store_->get_patient("P2").status().code(), StatusCode::kNotFound);
  const Counts after = this->counts();
  EXPECT_EQ(after.patients, before.patients);
  EXPECT_EQ(after.structures, before.structures);
  EXPECT_EQ(after.surfaces, before.surfaces);
}

TYPED_TEST(StoreWriteStructure, AgeIsGivenOrComputedAndFollowsTheBirthDate) {
  NewStructure s = new_structure("P1", "S1", "a");
  s.study.study_date = "20100601";
  ASSERT_TRUE(this->store_->add_structure(s).ok());
  EXPECT_FALSE(this->store_->get_study("S1")->age_years.has_value());  // no birth date yet

  NewStructure given = new_structure("P1", "S2", "b");
  given.study.study_date = "20100601";
  given.study.age_years = 42.5;
  ASSERT_TRUE(this->store_->add_structure(given).ok());

  NewStructure birth = new_structure("P1", "S3", "c");
  birth.patient.birth_date = "19800601";
  birth.study.study_date = "20200601";
  ASSERT_TRUE(this->store_->add_structure(birth).ok());
  EXPECT_EQ(*this->store_->get_study("S1")->age_years, 30.0);  // recomputed when the birth date arrived
  EXPECT_EQ(*this->store_->get_study("S2")->age_years, 42.5);  // a given age is kept
  EXPECT_EQ(*this->store_->get_study("S3")->age_years, 40.0);
}

TYPED_TEST(StoreWriteStructure, InvalidInputsAreInvalidArgumentNamingTheField) {
  struct Case {
    std::function<void(NewStructure&)> change;
    std::string phrase;
  };
  const std::vector<Case> cases = {
      {[](NewStructure& s) { s.patient.patient_id = std::string(""); }, "patient_id"},
      {[](NewStructure& s) { s.study.study_uid = std::string(""); }, "study_uid"},
      {[](NewStructure& s) { s.name = std::string(""); }, "name"},
      {[](NewStructure& s) { s.patient.sex = std::string("X"); }, "sex: 'X' is not a sex"},
      {[](NewStructure& s) { s.laterality = std::string("left"); }, "laterality: 'left' is not a laterality"},
      {[](NewStructure& s) { s.patient.birth_date = std::string("1960-01-01"); }, "birth date"},
      {[](NewStructure& s) { s.study.study_date = std::string("20201340"); }, "study date"},
      {[](NewStructure& s) { s.study.patient_id = std::string("P2"); }, "names patient 'P2'"},
      {[](NewStructure& s) { s.surface.sha256 = std::string("ABC"); }, "sha256"},
      // Not UTF-8 (Latin-1 bytes): PostgreSQL's text would refuse it in its own words, SQLite would
      // store it; both backends refuse it by the same rule before any SQL runs.
      {[](NewStructure& s) { s.name = std::string("GTV \xe9"); }, "structure name: 'GTV \xe9' is not UTF-8 text"},
      {[](NewStructure& s) { s.study.description = std::string("Cr\xe2ne"); }, "is not UTF-8 text"},
      {[](NewStructure& s) { s.patient.birth_date = std::string("20230229"); }, "is not a calendar date"},
  };
  for (const Case& c : cases) {
    NewStructure s = new_structure("P1", "S1", "x");
    c.change(s);
    auto r = this->store_->add_structure(s);
    ASSERT_FALSE(r.ok()) << c.phrase;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_TRUE(contains(r.status().message(), c.phrase)) << r.status().message();
  }
  EXPECT_EQ(this->counts().patients, 0);
}

// The same for a structure re-imported under its source UID (an RT Structure Set's ROI).
TYPED_TEST(StoreWriteStructure, StructureSourceOfAnotherPatientIsRefused) {
  NewStructure first = new_structure("P1", "S1", "a");
  first.source_uid = "1.2.3/1";
  auto added = this->store_->add_structure(first);
  ASSERT_TRUE(added.ok()) << added.status().to_string();
  NewStructure second = new_structure("P2", "S2", "a", 5.0);
  second.source_uid = "1.2.3/1";
  auto bad = this->store_->add_structure(second);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(bad.status().message(), "belongs to patient 'P1', not to 'P2'")) << bad.status().message();
  EXPECT_EQ(this->store_->get_patient("P2").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(this->store_->get_structure(added->structure.id)->study_uid, "S1");
}

}  // namespace
}  // namespace soiq::db
