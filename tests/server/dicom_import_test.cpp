// The DICOM import engine on its own, without gRPC: a folder of real files (STS_002's CT and its
// RT Structure Set) into a real SQLite store, the records it returns, the problems it reports, and
// an import the memory budget can never admit, which stores nothing.
#include "server/app/dicom_import.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "db/sqlite/sqlite_store.h"
#include "tests/db/temp_store.h"
#include "tests/support/sts_files.h"

namespace soiq::server {
namespace {

namespace fs = std::filesystem;
using db::testing::TempDir;

// STS_002's CT slices and structure set copied into `dir`, plus one file that is not DICOM.
std::vector<std::string> sts_002_ct(const std::string& dir) {
  std::vector<std::string> sent = soiq::testing::copy_sts_002_ct(SOIQ_TEST_DATA_DIR, dir);
  std::ofstream(fs::path(dir) / "notes.txt") << "not DICOM";
  sent.push_back("notes.txt");
  return sent;
}

int64_t count_series(db::Store& store) {
  auto page = store.list_patients({}, {});
  return page.ok() ? int64_t(page->items.size()) : -1;
}

// STS_002's CT received in a folder, and an empty store to import it into.
class DicomImport : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir);
    sent = sts_002_ct(dir);
    store = db::testing::open_store(tmp.file("soiq.db"));
  }
  Result<DicomImportResult> import(MemoryBudget& budget, bool keep_patient_names = false) {
    return import_dicom_folder(*store, dir, sent, int64_t(1) << 26, budget, {}, {keep_patient_names});
  }

  TempDir tmp;
  const std::string dir = tmp.file("received");
  std::vector<std::string> sent;
  std::unique_ptr<db::Store> store;
};

TEST_F(DicomImport, AFolderBecomesRecordsWithItsProblemsNamedByRelativePath) {
  MemoryBudget budget(int64_t(1) << 30);
  Result<DicomImportResult> r = import(budget);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->files_received, 50);
  EXPECT_EQ(r->dicom_files_read, 49);
  ASSERT_EQ(r->patients.size(), 1u);
  EXPECT_EQ(r->patients[0].patient_id, "STS_002");
  ASSERT_EQ(r->studies.size(), 1u);
  ASSERT_EQ(r->series.size(), 1u);
  EXPECT_EQ(r->series[0].modality, "CT");
  ASSERT_FALSE(r->structures.empty());
  bool gtv = false;
  for (const ImportedStructure& s : r->structures) {
    EXPECT_GT(s.structure.id, 0);
    EXPECT_EQ(s.referenced_series_uid, r->series[0].series_uid);
    EXPECT_GT(s.voxel_count, 0);
    EXPECT_FALSE(s.replaced);
    gtv = gtv || s.structure.name.rfind("GTV_Mass", 0) == 0;
  }
  EXPECT_TRUE(gtv);
  bool named = false;
  for (const ImportProblem& p : r->problems) {
    EXPECT_EQ(p.path.find(dir), std::string::npos) << "paths are relative to the folder: " << p.path;
    EXPECT_EQ(p.message.find(dir), std::string::npos) << p.message;
    named = named || p.message.find("not DICOM") != std::string::npos;
  }
  EXPECT_TRUE(named);
  EXPECT_EQ(budget.in_use(), 0);  // given back once written
  EXPECT_GT(budget.peak(), 0);

  // The same files again: the structures are the stored ones, updated in place.
  Result<DicomImportResult> again = import(budget);
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  ASSERT_EQ(again->structures.size(), r->structures.size());
  for (size_t i = 0; i < again->structures.size(); ++i) {
    EXPECT_EQ(again->structures[i].structure.id, r->structures[i].structure.id);
    EXPECT_TRUE(again->structures[i].replaced);
  }
  // Without --keep-patient-names the name is dropped; the series keeps its number and description.
  EXPECT_EQ(store->get_patient("STS_002")->patient_name, "");
  Result<db::SeriesRecord> series = store->get_series(r->series[0].series_uid);
  ASSERT_TRUE(series.ok());
  EXPECT_EQ(series->series_number, 3);
  EXPECT_EQ(series->description, "IBSI_1_STS_002_CT_image");
}

// The files declare ISO_IR 100 (Latin-1): the name is stored converted to UTF-8, and only when asked.
TEST_F(DicomImport, ThePatientsNameIsKeptOnlyWhenAsked) {
  MemoryBudget budget(int64_t(1) << 30);
  Result<DicomImportResult> r = import(budget, true);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(store->get_patient("STS_002")->patient_name, "STS_002");
}

TEST_F(DicomImport, AnImportTheBudgetCanNeverAdmitStoresNothing) {
  MemoryBudget budget(int64_t(1) << 20);
  Result<DicomImportResult> r = import(budget);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted) << r.status().to_string();
  EXPECT_NE(r.status().message().find("161x143x48"), std::string::npos) << r.status().message();
  EXPECT_EQ(count_series(*store), 0);
  EXPECT_EQ(budget.peak(), 0);
}

TEST(DicomImportNothing, NothingImportableIsInvalidArgumentNamingTheFile) {
  TempDir tmp;
  const std::string dir = tmp.file("received");
  fs::create_directories(dir);
  std::ofstream(fs::path(dir) / "notes.txt") << "not DICOM";
  auto store = db::testing::open_store(tmp.file("soiq.db"));
  MemoryBudget budget(int64_t(1) << 30);
  Result<DicomImportResult> r = import_dicom_folder(*store, dir, {"notes.txt"}, int64_t(1) << 26, budget, {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("nothing could be imported from the 1 file(s) sent"), std::string::npos)
      << r.status().message();
}

}  // namespace
}  // namespace soiq::server
