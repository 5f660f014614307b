// What every Store backend must do (db/store.h), one behaviour per test, written against the
// interface alone and run on each backend of store_backends.h (SQLite, PostgreSQL).
// Backend-specific behaviour (files, pragmas, migrations, concurrency of one engine) stays in that
// backend's own tests.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>
#include <string>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_series;
using testing::new_structure;
using testing::TempDir;

template <typename Backend>
class StoreConformance : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = Backend::open(dir_);
    ASSERT_NE(store_, nullptr);
  }
  Store& store() { return *store_; }
  int64_t add(const std::string& patient, const std::string& study, const std::string& name, double offset,
              const std::string& laterality = "") {
    NewStructure s = new_structure(patient, study, name, offset);
    s.laterality = laterality;
    Result<AddedStructure> added = store_->add_structure(s);
    EXPECT_TRUE(added.ok()) << added.status().to_string();
    return added.ok() ? added->structure.id : -1;
  }
  Counts counts() {
    Result<Counts> c = store_->counts();
    EXPECT_TRUE(c.ok());
    return c.ok() ? *c : Counts{};
  }

  TempDir dir_;
  std::unique_ptr<Store> store_;
};

TYPED_TEST_SUITE(StoreConformance, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreConformance, AnAddedStructureReadsBackWithItsPatientStudyAndSurface) {
  NewStructure s = new_structure("P1", "1.2.3", "Hippocampus", 1);
  s.laterality = "L";
  Result<AddedStructure> added = this->store().add_structure(s);
  ASSERT_TRUE(added.ok()) << added.status().to_string();
  Result<StructureRecord> back = this->store().get_structure(added->structure.id);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->name, "Hippocampus");
  EXPECT_EQ(back->laterality, "L");
  EXPECT_EQ(back->patient_id, "P1");
  EXPECT_EQ(back->study_uid, "1.2.3");
  EXPECT_EQ(back->surface.sha256, s.surface.sha256);
  Result<std::string> blob = this->store().get_surface_blob(s.surface.sha256);
  ASSERT_TRUE(blob.ok());
  EXPECT_EQ(*blob, s.surface_blob);
  EXPECT_TRUE(this->store().get_patient("P1").ok());
  EXPECT_TRUE(this->store().get_study("1.2.3").ok());
}

TYPED_TEST(StoreConformance, TheSameSurfaceIsStoredOnce) {
  this->add("P1", "S1", "a", 7);
  Result<AddedStructure> second = this->store().add_structure(new_structure("P2", "S2", "b", 7));
  ASSERT_TRUE(second.ok());
  EXPECT_TRUE(second->surface_already_stored);
  EXPECT_EQ(this->counts().structures, 2);
  EXPECT_EQ(this->counts().surfaces, 1);
}

TYPED_TEST(StoreConformance, UnknownIdsAreNotFoundNamingTheId) {
  Store& s = this->store();
  EXPECT_EQ(s.get_structure(42).status().code(), StatusCode::kNotFound);
  EXPECT_TRUE(contains(s.get_structure(42).status().message(), "42"));
  EXPECT_EQ(s.get_patient("nobody").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(s.get_study("9.9").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(s.get_series("9.9.9").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(s.get_image_blob("9.9.9").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(s.get_surface_blob("00").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(s.delete_structure(42).status().code(), StatusCode::kNotFound);
  EXPECT_EQ(s.delete_patient("nobody").status().code(), StatusCode::kNotFound);
}

TYPED_TEST(StoreConformance, ASeriesIsReplacedByItsUidWithItsNewImage) {
  Result<bool> first = this->store().put_series(new_series("P1", "S1", "S1.1", 1.0f));
  ASSERT_TRUE(first.ok()) << first.status().to_string();
  EXPECT_FALSE(*first);
  const NewSeries again = new_series("P1", "S1", "S1.1", 2.0f);
  Result<bool> second = this->store().put_series(again);
  ASSERT_TRUE(second.ok());
  EXPECT_TRUE(*second);
  Result<std::string> blob = this->store().get_image_blob("S1.1");
  ASSERT_TRUE(blob.ok());
  EXPECT_EQ(*blob, again.image_blob);
  Result<std::vector<SeriesRecord>> listed = this->store().list_series("S1");
  ASSERT_TRUE(listed.ok());
  ASSERT_EQ(listed->size(), 1u);
  EXPECT_EQ((*listed)[0].sha256, again.series.sha256);
}

// A gantry-tilted, unevenly spaced series keeps its grid exactly: the leaning k axis, and where
// each slice lies (the image decodes on it, its sha256 covering them).
TYPED_TEST(StoreConformance, AnIrregularSeriesKeepsItsSlicePositionsAndTilt) {
  NewSeries s = new_series("P1", "S1", "S1.9", 1.5f);
  Image image;
  image.geometry = s.series.geometry;
  image.geometry.dims = {3, 2, 4};
  image.geometry.slice_positions_mm = {0, 1.25, 3.75, 8.75};
  image.geometry.spacing_mm[2] = image.geometry.slice_positions_mm.back() / 3;
  const double lean = 0.2588190451025208;  // sin 15 degrees
  image.geometry.direction = {{{1, 0, 0}, {0, 1, lean}, {0, 0, std::sqrt(1 - lean * lean)}}};
  image.voxels.assign(24, 1.5f);
  ASSERT_TRUE(validate_geometry(image.geometry).ok()) << validate_geometry(image.geometry).to_string();
  auto encoded = encode_image(image);
  ASSERT_TRUE(encoded.ok());
  EXPECT_NE(encoded->sha256, new_series("P1", "S1", "S1.9", 1.5f).series.sha256);
  s.series.geometry = image.geometry;
  s.series.sha256 = encoded->sha256;
  s.image_blob = encoded->blob;
  ASSERT_TRUE(this->store().put_series(s).ok());
  Result<std::vector<SeriesRecord>> listed = this->store().list_series("S1");
  ASSERT_TRUE(listed.ok());
  ASSERT_EQ(listed->size(), 1u);
  EXPECT_EQ((*listed)[0].geometry, image.geometry);
  Result<std::string> blob = this->store().get_image_blob("S1.9");
  ASSERT_TRUE(blob.ok());
  auto decoded = decode_image(*blob, (*listed)[0].geometry);
  ASSERT_TRUE(decoded.ok()) << decoded.status().to_string();
  EXPECT_EQ(decoded->voxels, image.voxels);
}

TYPED_TEST(StoreConformance, CountsListEachModalityOfTheSeriesOnceInOrder) {
  EXPECT_TRUE(this->counts().series_modalities.empty());
  int n = 0;
  for (const char* modality : {"PT", "MR", "PT", "CT", "MR", "PT"}) {
    ++n;
    NewSeries s = new_series("P1", "S1", "S1." + std::to_string(n), float(n));
    s.series.modality = modality;
    ASSERT_TRUE(this->store().put_series(s).ok());
  }
  EXPECT_EQ(this->counts().series, 6);
  EXPECT_EQ(this->counts().series_modalities, (std::vector<std::string>{"CT", "MR", "PT"}));
}

TYPED_TEST(StoreConformance, AnImportBatchWithOneRefusedRecordStoresNothing) {
  this->add("P1", "S1", "kept", 1);
  const Counts before = this->counts();
  ImportBatch b;
  b.series.push_back(new_series("P2", "S2", "S2.1", 1.0f));
  b.structures.push_back(new_structure("P2", "S2", "fine", 2));
  b.structures.push_back(new_structure("P2", "S1", "in another patient's study", 3));
  Result<ImportedBatch> r = this->store().import_batch(b);
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition);
  const Counts after = this->counts();
  EXPECT_EQ(after.patients, before.patients);
  EXPECT_EQ(after.series, before.series);
  EXPECT_EQ(after.structures, before.structures);
  EXPECT_EQ(this->store().get_patient("P2").status().code(), StatusCode::kNotFound);
}

TYPED_TEST(StoreConformance, AStudyNeverChangesPatientAndTheRefusalNamesBoth) {
  this->add("P1", "S1", "a", 1);
  Result<AddedStructure> r = this->store().add_structure(new_structure("P2", "S1", "b", 2));
  ASSERT_EQ(r.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(r.status().message(), "P1")) << r.status().message();
  EXPECT_TRUE(contains(r.status().message(), "P2")) << r.status().message();
}

TYPED_TEST(StoreConformance, PagesListEveryStructureOnceInIdOrder) {
  std::vector<int64_t> added;
  for (int i = 0; i < 7; ++i)
    added.push_back(this->add("P" + std::to_string(i % 3), "S" + std::to_string(i % 3), "s", i));
  std::vector<int64_t> seen;
  PageRequest page;
  page.page_size = 3;
  do {
    Result<Page<StructureRecord>> p = this->store().list_structures({}, page);
    ASSERT_TRUE(p.ok()) << p.status().to_string();
    for (const StructureRecord& s : p->items) seen.push_back(s.id);
    page.page_token = p->next_page_token;
  } while (!page.page_token.empty());
  EXPECT_EQ(seen, added);
}

TYPED_TEST(StoreConformance, Stage1KeepsWhatTheFilterSaysInIdOrder) {
  NewStructure f = new_structure("P1", "S1", "Hippocampus", 1);
  f.patient.sex = "F";
  NewStructure m = new_structure("P2", "S2", "hippocampus", 2);
  m.patient.sex = "M";
  NewStructure other = new_structure("P3", "S3", "amygdala", 3);
  other.patient.sex = "F";
  const int64_t fid = this->store().add_structure(f)->structure.id;
  ASSERT_TRUE(this->store().add_structure(m).ok());
  ASSERT_TRUE(this->store().add_structure(other).ok());
  Stage1Filter filter;
  filter.sex = "F";
  filter.structure_name_glob = "HIPPO*";
  Result<std::vector<Candidate>> r = this->store().stage1(filter, 10);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  ASSERT_EQ(r->size(), 1u);
  EXPECT_EQ((*r)[0].structure.id, fid);
  EXPECT_EQ((*r)[0].patient.patient_id, "P1");
  EXPECT_EQ((*r)[0].study.study_uid, "S1");
}

TYPED_TEST(StoreConformance, Stage1OverItsLimitIsResourceExhaustedWithTheCount) {
  for (int i = 0; i < 4; ++i) this->add("P", "S", "s", i);
  Result<std::vector<Candidate>> r = this->store().stage1({}, 3);
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted);
  EXPECT_TRUE(contains(r.status().message(), "4")) << r.status().message();
}

TYPED_TEST(StoreConformance, Stage1FindsTheTwinOnlyWhenAsked) {
  const int64_t left = this->add("P", "S", "Caudate", 1, "L");
  const int64_t right = this->add("P", "S", "caudate", 2, "R");
  Stage1Filter filter;
  filter.laterality = "L";
  Result<std::vector<Candidate>> plain = this->store().stage1(filter, 10);
  ASSERT_TRUE(plain.ok());
  ASSERT_EQ(plain->size(), 1u);
  EXPECT_FALSE((*plain)[0].twin);
  filter.twins = true;
  Result<std::vector<Candidate>> with = this->store().stage1(filter, 10);
  ASSERT_TRUE(with.ok());
  ASSERT_EQ(with->size(), 1u);
  EXPECT_EQ((*with)[0].structure.id, left);
  ASSERT_TRUE((*with)[0].twin);
  EXPECT_EQ((*with)[0].twin->id, right);
}

TYPED_TEST(StoreConformance, CachedFeaturesReadBackByKeyAndGoWithTheirSurface) {
  NewStructure s = new_structure("P", "S", "s", 1);
  const int64_t id = this->store().add_structure(s)->structure.id;
  const std::vector<CachedFeature> entries = {{"k1", "volume", {1.5}}, {"k1", "centroid", {1, 2, 3}}, {"k2", "a", {4}}};
  ASSERT_TRUE(this->store().put_cached_features(s.surface.sha256, entries).ok());
  Result<std::vector<CachedFeature>> k1 = this->store().cached_features({"k1"});
  ASSERT_TRUE(k1.ok());
  std::set<std::string> names;
  for (const CachedFeature& e : *k1) {
    EXPECT_EQ(e.key, "k1");
    names.insert(e.entry);
    if (e.entry == "centroid") {
      EXPECT_EQ(e.value, (std::vector<double>{1, 2, 3}));
    }
  }
  EXPECT_EQ(names, (std::set<std::string>{"volume", "centroid"}));
  ASSERT_TRUE(this->store().delete_structure(id).ok());
  Result<std::vector<CachedFeature>> gone = this->store().cached_features({"k1", "k2"});
  ASSERT_TRUE(gone.ok());
  EXPECT_TRUE(gone->empty());
  EXPECT_EQ(this->counts().surfaces, 0);
}

TYPED_TEST(StoreConformance, DeletingAPatientRemovesEverythingOfItAndNothingElse) {
  this->add("P1", "S1", "a", 1);
  this->add("P1", "S1", "b", 2);
  ASSERT_TRUE(this->store().put_series(new_series("P1", "S1", "S1.1", 1.0f)).ok());
  this->add("P2", "S2", "c", 3);
  Result<int64_t> removed = this->store().delete_patient("P1");
  ASSERT_TRUE(removed.ok());
  EXPECT_EQ(*removed, 2);
  const Counts c = this->counts();
  EXPECT_EQ(c.patients, 1);
  EXPECT_EQ(c.studies, 1);
  EXPECT_EQ(c.series, 0);
  EXPECT_EQ(c.structures, 1);
  EXPECT_EQ(c.surfaces, 1);
  EXPECT_EQ(this->store().get_image_blob("S1.1").status().code(), StatusCode::kNotFound);
}

}  // namespace
}  // namespace soiq::db
