// NewStructure::same_content_is_same_structure: a structure coming back (soiq's own SEG export
// imported again) is recognised as the stored one, never stored twice; anything that differs is new.
#include <gtest/gtest.h>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_series;
using testing::new_structure;

// The original: an RT Structure Set ROI on series 1.2.3.4.
NewStructure original() {
  NewStructure s = new_structure("P1", "1.2.3", "GTV", 0);
  s.source_series_uid = "1.2.3.4";
  s.source_uid = "1.2.3.77/1";
  return s;
}

// The same voxels back from a SEG (another source uid), as the import marks it.
NewStructure from_seg(const std::string& name = "GTV", double surface_offset = 0) {
  NewStructure s = new_structure("P1", "1.2.3", name, surface_offset);
  s.source_series_uid = "1.2.3.4";
  s.source_uid = "1.2.3.88/1";
  s.same_content_is_same_structure = true;
  return s;
}

template <typename Backend>
class StoreSameContent : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreSameContent, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreSameContent, SegmentRepeatingAStoredStructureIsRecognisedAndNothingIsWritten) {
  Store* store = this->store_.get();
  ASSERT_TRUE(store->put_series(new_series("P1", "1.2.3", "1.2.3.4", 1.0f)).ok());
  auto first = store->add_structure(original());
  ASSERT_TRUE(first.ok()) << first.status().to_string();
  for (int i = 0; i < 2; ++i) {
    auto again = store->add_structure(from_seg());
    ASSERT_TRUE(again.ok()) << again.status().to_string();
    EXPECT_TRUE(again->recognised);
    EXPECT_FALSE(again->replaced);
    EXPECT_EQ(again->structure.id, first->structure.id);
    EXPECT_EQ(again->structure.source_uid, "1.2.3.77/1");  // still the original's
  }
  EXPECT_EQ(store->counts()->structures, 1);
  // The original's own re-import still finds it by its source uid.
  auto rt = store->add_structure(original());
  ASSERT_TRUE(rt.ok());
  EXPECT_TRUE(rt->replaced);
  EXPECT_EQ(store->counts()->structures, 1);
}

TYPED_TEST(StoreSameContent, OtherVoxelsOtherNameOrNoFlagMakeANewStructure) {
  Store* store = this->store_.get();
  ASSERT_TRUE(store->put_series(new_series("P1", "1.2.3", "1.2.3.4", 1.0f)).ok());
  ASSERT_TRUE(store->add_structure(original()).ok());
  auto edited = store->add_structure(from_seg("GTV", 1));  // other voxels
  ASSERT_TRUE(edited.ok());
  EXPECT_FALSE(edited->recognised);
  NewStructure renamed = from_seg("GTV_reviewed");
  renamed.source_uid = "1.2.3.88/2";
  auto other_name = store->add_structure(renamed);
  ASSERT_TRUE(other_name.ok());
  EXPECT_FALSE(other_name->recognised);
  NewStructure unflagged = from_seg();
  unflagged.source_uid = "1.2.3.99/1";
  unflagged.same_content_is_same_structure = false;
  ASSERT_TRUE(store->add_structure(unflagged).ok());
  EXPECT_EQ(store->counts()->structures, 4);
}

TYPED_TEST(StoreSameContent, SameVoxelsInAnotherStudyAreAnotherStructure) {
  Store* store = this->store_.get();
  ASSERT_TRUE(store->add_structure(original()).ok());
  NewStructure elsewhere = from_seg();
  elsewhere.study.study_uid = "1.2.4";
  auto r = store->add_structure(elsewhere);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_FALSE(r->recognised);
  EXPECT_EQ(store->counts()->structures, 2);
}

}  // namespace
}  // namespace soiq::db
