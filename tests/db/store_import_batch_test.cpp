// Store::import_batch, on every backend: series and structures of one import in one transaction.
#include <gtest/gtest.h>

#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_series;
using testing::new_structure;
using testing::two_series_two_structures;

template <typename Backend>
class StoreImportBatch : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreImportBatch, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreImportBatch, StoresEverySeriesAndStructure) {
  auto r = this->store_->import_batch(two_series_two_structures());
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->series_replaced, (std::vector<bool>{false, false}));
  ASSERT_EQ(r->structures.size(), 2u);
  EXPECT_EQ(r->structures[0].structure.name, "GTV_CT");
  EXPECT_EQ(r->structures[1].structure.study_uid, "S1");
  const Counts n = this->counts();
  EXPECT_EQ(n.patients, 1);
  EXPECT_EQ(n.studies, 1);
  EXPECT_EQ(n.series, 2);
  EXPECT_EQ(n.structures, 2);
  // Stage 1 sees the series' modalities for the structures written after them.
  Stage1Filter f;
  f.modality = "PT";
  auto hits = this->store_->stage1(f, 10);
  ASSERT_TRUE(hits.ok());
  EXPECT_EQ(hits->size(), 2u);
}

TYPED_TEST(StoreImportBatch, InvalidItemIsRefusedBeforeAnyWrite) {
  ImportBatch b = two_series_two_structures();
  b.structures[1].laterality = "X";
  auto r = this->store_->import_batch(b);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(this->counts().series, 0);
  EXPECT_EQ(this->counts().patients, 0);
}

// A structure set holds ROIs 1 and 2; the same SOP Instance UID sent again with ROI 1 alone is
// another content, refused naming the ROI it lacks, and nothing changes. Asked to replace, it goes in.
TYPED_TEST(StoreImportBatch, AnObjectSentAgainWithoutAStoredRoiIsAlreadyExistsNamingIt) {
  ImportBatch first;
  first.series.push_back(new_series("P1", "1.2.3", "1.2.3.4", 1.0f));
  NewStructure roi1 = testing::imported_structure("GTV", 1.0);
  roi1.replace_other_content = false;
  NewStructure roi2 = testing::imported_structure("CTV", 2.0);
  roi2.source_uid = "1.2.3.77/2";
  roi2.replace_other_content = false;
  first.structures = {roi1, roi2};
  auto stored = this->store_->import_batch(first);
  ASSERT_TRUE(stored.ok()) << stored.status().to_string();
  const int64_t ctv_id = stored->structures[1].structure.id;

  ImportBatch again;
  again.structures = {roi1};
  auto refused = this->store_->import_batch(again);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kAlreadyExists);
  EXPECT_EQ(refused.status().message(),
            "DICOM object '1.2.3.77' is stored with ROI 2 ('CTV', structure " + std::to_string(ctv_id) +
                "), which the object sent does not hold; a DICOM UID names one content: send the object as "
                "stored, or replace it (soiq import --replace)");
  EXPECT_EQ(this->counts().structures, 2);

  // The same object whole is a no-op; an object of another UID is not compared with this one.
  again.structures = {roi2, roi1};
  ASSERT_TRUE(this->store_->import_batch(again).ok());
  NewStructure other = testing::imported_structure("GTV_other", 3.0);
  other.source_uid = "1.2.3.770/1";  // shares the prefix '1.2.3.77' but is another object
  other.replace_other_content = false;
  again.structures = {other};
  auto separate = this->store_->import_batch(again);
  ASSERT_TRUE(separate.ok()) << separate.status().to_string();
  EXPECT_EQ(this->counts().structures, 3);

  // Replacing: ROI 1 alone is accepted (and ROI 2 stays, as a replace of one ROI leaves the others).
  roi1.replace_other_content = true;
  again.structures = {roi1};
  ASSERT_TRUE(this->store_->import_batch(again).ok());
}

// The same ROI of the same object with another surface (other contours, or another SEG segment's
// voxels) is another content: refused naming both surfaces, unless replaced.
TYPED_TEST(StoreImportBatch, AnRoiSentAgainWithAnotherSurfaceIsAlreadyExistsUnlessReplaced) {
  ImportBatch first;
  first.series.push_back(new_series("P1", "1.2.3", "1.2.3.4", 1.0f));
  NewStructure roi = testing::imported_structure("GTV", 1.0);
  roi.replace_other_content = false;
  first.structures = {roi};
  auto stored = this->store_->import_batch(first);
  ASSERT_TRUE(stored.ok()) << stored.status().to_string();

  NewStructure changed = testing::imported_structure("GTV", 5.0);
  changed.replace_other_content = false;
  ASSERT_NE(changed.surface.sha256, roi.surface.sha256);
  ImportBatch again;
  again.structures = {changed};
  auto refused = this->store_->import_batch(again);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kAlreadyExists);
  EXPECT_NE(refused.status().message().find("ROI 1 of DICOM object '1.2.3.77' is stored as structure " +
                                            std::to_string(stored->structures[0].structure.id) +
                                            " with another surface (sha256 " + roi.surface.sha256.substr(0, 12) +
                                            "... stored, " + changed.surface.sha256.substr(0, 12) + "... sent)"),
            std::string::npos)
      << refused.status().message();
  auto kept = this->store_->get_structure(stored->structures[0].structure.id);
  ASSERT_TRUE(kept.ok());
  EXPECT_EQ(kept->surface.sha256, roi.surface.sha256);

  changed.replace_other_content = true;
  again.structures = {changed};
  auto replaced = this->store_->import_batch(again);
  ASSERT_TRUE(replaced.ok()) << replaced.status().to_string();
  EXPECT_EQ(replaced->structures[0].structure.id, stored->structures[0].structure.id);
  EXPECT_TRUE(replaced->structures[0].replaced);
  kept = this->store_->get_structure(stored->structures[0].structure.id);
  ASSERT_TRUE(kept.ok());
  EXPECT_EQ(kept->surface.sha256, changed.surface.sha256);
}

}  // namespace
}  // namespace soiq::db
