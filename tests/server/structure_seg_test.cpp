// Imported structures as one DICOM SEG, on its own: STS_002's CT and RT Structure Set imported into
// a real store, the GTV written as a SEG on the CT's grid, and the refusals for structures a SEG
// cannot hold.
#include "server/app/structure_seg.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "db/surface_blob.h"
#include "server/app/dicom_import.h"
#include "tests/db/temp_store.h"
#include "tests/support/sts_files.h"

namespace soiq::server {
namespace {

namespace fs = std::filesystem;
using db::testing::TempDir;

class StructureSeg : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string dir = tmp_.file("received");
    fs::create_directories(dir);
    const std::vector<std::string> sent = soiq::testing::copy_sts_002_ct(SOIQ_TEST_DATA_DIR, dir);
    Result<DicomImportResult> r = import_dicom_folder(*store_, dir, sent, int64_t(1) << 26, budget_, {});
    ASSERT_TRUE(r.ok()) << r.status().to_string();
    for (const ImportedStructure& s : r->structures) imported_.push_back(s.structure.id);
    ASSERT_FALSE(imported_.empty());
  }

  TempDir tmp_;
  std::unique_ptr<db::SqliteStore> store_ = db::testing::open_store(tmp_.file("soiq.db"));
  MemoryBudget budget_{int64_t(1) << 30};
  FeatureEngine features_{*store_, int64_t(1) << 26, budget_};
  std::vector<int64_t> imported_;
};

TEST_F(StructureSeg, ImportedStructuresBecomeOneSegOnTheirSeries) {
  Result<BudgetedSeg> written = structure_seg(*store_, features_, budget_, imported_, "GTV as SEG");
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  const dicom::WrittenSeg& seg = written->seg;
  ASSERT_GT(seg.bytes.size(), 132u);
  EXPECT_EQ(seg.bytes.substr(128, 4), "DICM");  // a Part 10 file
  EXPECT_GT(seg.frame_count, 0);
  EXPECT_FALSE(seg.series_uid.empty());
  EXPECT_FALSE(seg.sop_instance_uid.empty());
  // The SEG's bytes stay counted in the budget while they are held, and only they.
  EXPECT_GE(budget_.in_use(), int64_t(seg.bytes.size()));
  EXPECT_EQ(budget_.in_use(), written->held.bytes());
  written = Result<BudgetedSeg>(not_found("dropped"));
  EXPECT_EQ(budget_.in_use(), 0);
}

TEST_F(StructureSeg, ASegThatCanNeverFitTheBudgetIsRefusedBeforeItIsWritten) {
  MemoryBudget small(int64_t(64) << 10);
  FeatureEngine features(*store_, int64_t(1) << 26, small);
  Result<BudgetedSeg> written = structure_seg(*store_, features, small, imported_, "");
  EXPECT_EQ(written.status().code(), StatusCode::kResourceExhausted) << written.status().to_string();
  EXPECT_EQ(small.in_use(), 0);
}

TEST_F(StructureSeg, NoIdsOrARepeatedIdIsInvalidArgument) {
  EXPECT_EQ(structure_seg(*store_, features_, budget_, {}, "").status().code(), StatusCode::kInvalidArgument);
  const std::vector<int64_t> twice = {imported_[0], imported_[0]};
  EXPECT_EQ(structure_seg(*store_, features_, budget_, twice, "").status().code(), StatusCode::kInvalidArgument);
}

TEST_F(StructureSeg, AnUnknownStructureIsNotFound) {
  EXPECT_EQ(structure_seg(*store_, features_, budget_, {imported_.back() + 100}, "").status().code(),
            StatusCode::kNotFound);
}

TEST_F(StructureSeg, AnUploadedStructureHasNoImagesToReferenceAndSaysHowToGetThem) {
  Result<db::AddedStructure> uploaded = store_->add_structure(db::testing::new_structure("P", "S", "uploaded", 1));
  ASSERT_TRUE(uploaded.ok());
  Result<BudgetedSeg> seg = structure_seg(*store_, features_, budget_, {uploaded->structure.id}, "");
  EXPECT_EQ(seg.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(seg.status().message().find("soiq import"), std::string::npos) << seg.status().message();
}

}  // namespace
}  // namespace soiq::server
