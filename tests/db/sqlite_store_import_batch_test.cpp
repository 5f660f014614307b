// SqliteStore::import_batch failing on its last structure, by a trigger installed in the SQLite
// file as another client could: nothing of the batch is kept (the batch's other behaviour is tested
// on every backend in store_import_batch_test.cpp).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "db/sqlite/sqlite_store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_series;
using testing::new_structure;
using testing::two_series_two_structures;

class SqliteStoreImportBatch : public testing::StoreTest<testing::SqliteBackend> {};

TEST_F(SqliteStoreImportBatch, FailureOnTheLastStructureLeavesNothing) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(dir_.file("store.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "CREATE TRIGGER fail BEFORE INSERT ON structures WHEN NEW.name = 'GTV_PT' "
                         "BEGIN SELECT RAISE(ABORT, 'injected failure'); END",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  auto r = store_->import_batch(two_series_two_structures());
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.status().message(), "injected failure")) << r.status().message();
  const Counts n = counts();
  EXPECT_EQ(n.patients, 0);
  EXPECT_EQ(n.studies, 0);
  EXPECT_EQ(n.series, 0);
  EXPECT_EQ(n.structures, 0);
  EXPECT_EQ(n.surfaces, 0);
}

}  // namespace
}  // namespace soiq::db
