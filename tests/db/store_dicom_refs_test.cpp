// The DICOM references of series (for SEG export) and the source of imported structures (a
// re-import updates in place), on every backend.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::imported_structure;
using testing::new_series;
using testing::new_structure;

NewSeries series_with_references() {
  NewSeries s = new_series("P1", "1.2.3", "1.2.3.4", 1.0f);
  s.series.frame_of_reference_uid = "1.2.3.99";
  s.series.sop_class_uid = "1.2.840.10008.5.1.4.1.1.4";
  s.series.slice_instance_uids = {"1.2.3.4.1", "1.2.3.4.2"};  // dims[2] == 2
  return s;
}

template <typename Backend>
class StoreDicomRefs : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreDicomRefs, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreDicomRefs, SeriesReferencesRoundTrip) {
  Store* store = this->store_.get();
  ASSERT_TRUE(store->put_series(series_with_references()).ok());
  auto got = store->get_series("1.2.3.4");
  ASSERT_TRUE(got.ok()) << got.status().to_string();
  EXPECT_EQ(got->frame_of_reference_uid, "1.2.3.99");
  EXPECT_EQ(got->sop_class_uid, "1.2.840.10008.5.1.4.1.1.4");
  EXPECT_EQ(got->slice_instance_uids, (std::vector<std::string>{"1.2.3.4.1", "1.2.3.4.2"}));
  // A series without DICOM references reads back with none.
  ASSERT_TRUE(store->put_series(new_series("P1", "1.2.3", "1.2.3.5", 2.0f)).ok());
  auto plain = store->get_series("1.2.3.5");
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(plain->slice_instance_uids.empty());
  EXPECT_EQ(plain->frame_of_reference_uid, "");
}

TYPED_TEST(StoreDicomRefs, BadReferencesAreRefusedNamingTheField) {
  Store* store = this->store_.get();
  NewSeries wrong_count = series_with_references();
  wrong_count.series.slice_instance_uids.pop_back();
  auto r = store->put_series(wrong_count);
  ASSERT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(r.status().message(), "1 slice instance uids for 2 slices")) << r.status().message();

  NewSeries backslash = series_with_references();
  backslash.series.slice_instance_uids[1] = "1.2\\3";  // would split into two on reading
  r = store->put_series(backslash);
  ASSERT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(r.status().message(), "slice instance uid: '1.2\\3'")) << r.status().message();

  NewStructure s = imported_structure("GTV", 0);
  s.source_series_uid = "not a uid";
  auto added = store->add_structure(s);
  ASSERT_EQ(added.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(added.status().message(), "source_series_uid")) << added.status().message();
  EXPECT_EQ(store->counts()->series, 0);
  EXPECT_EQ(store->counts()->structures, 0);
}

TYPED_TEST(StoreDicomRefs, SameSourceUidUpdatesTheStructureInPlace) {
  Store* store = this->store_.get();
  ImportBatch first;
  first.series.push_back(series_with_references());
  first.structures.push_back(imported_structure("GTV", 0));
  auto a = store->import_batch(first);
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  ASSERT_EQ(a->structures.size(), 1u);
  EXPECT_FALSE(a->structures[0].replaced);
  const int64_t id = a->structures[0].structure.id;
  EXPECT_EQ(a->structures[0].structure.source_uid, "1.2.3.77/1");
  EXPECT_EQ(a->structures[0].structure.source_series_uid, "1.2.3.4");

  // The same ROI again, renamed and with another surface: one structure, same id, new values,
  // and the old surface is gone with its last reference.
  ImportBatch again = first;
  again.structures[0] = imported_structure("GTV_Mass", 5);
  auto b = store->import_batch(again);
  ASSERT_TRUE(b.ok()) << b.status().to_string();
  EXPECT_TRUE(b->structures[0].replaced);
  EXPECT_EQ(b->structures[0].structure.id, id);
  EXPECT_EQ(b->structures[0].structure.name, "GTV_Mass");
  EXPECT_EQ(b->structures[0].structure.surface.sha256, again.structures[0].surface.sha256);
  const Counts n = *store->counts();
  EXPECT_EQ(n.structures, 1);
  EXPECT_EQ(n.surfaces, 1);
  // Stage 1 sees the new name only.
  Stage1Filter f;
  f.structure_name_glob = "gtv_mass";
  EXPECT_EQ(store->stage1(f, 10)->size(), 1u);
  f.structure_name_glob = "gtv";
  EXPECT_EQ(store->stage1(f, 10)->size(), 0u);

  // Uploads (no source_uid) never merge.
  ASSERT_TRUE(store->add_structure(new_structure("P1", "1.2.3", "GTV_Mass", 5)).ok());
  ASSERT_TRUE(store->add_structure(new_structure("P1", "1.2.3", "GTV_Mass", 5)).ok());
  EXPECT_EQ(store->counts()->structures, 3);
}

}  // namespace
}  // namespace soiq::db
