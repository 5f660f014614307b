// SqliteStore writes of structures that need the SQLite file itself: a failure injected late in
// add_structure's transaction by a trigger another client installs (the same behaviour through the
// Store interface runs on every backend in store_write_structure_test.cpp).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "db/sqlite/sqlite_store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_structure;

class SqliteStoreWriteStructure : public testing::StoreTest<testing::SqliteBackend> {};

TEST_F(SqliteStoreWriteStructure, FailureLateInTheTransactionLeavesNothing) {
  // A trigger (installed as another client could) makes the last insert of add_structure fail,
  // after the patient, study and surface rows were written in the same transaction.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(dir_.file("store.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "CREATE TRIGGER fail BEFORE INSERT ON structures WHEN NEW.name = 'boom' "
                         "BEGIN SELECT RAISE(ABORT, 'injected failure'); END",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  NewStructure s = new_structure("P9", "S9", "boom", 9.0);
  s.patient.birth_date = "19500101";
  auto r = store_->add_structure(s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInternal);
  EXPECT_TRUE(contains(r.status().message(), "injected failure")) << r.status().message();
  const Counts n = counts();
  EXPECT_EQ(n.patients, 0);
  EXPECT_EQ(n.studies, 0);
  EXPECT_EQ(n.surfaces, 0);
  EXPECT_EQ(n.structures, 0);
  // The store is usable afterwards: the transaction was closed.
  EXPECT_TRUE(store_->add_structure(new_structure("P9", "S9", "fine", 9.0)).ok());
}

}  // namespace
}  // namespace soiq::db
