// A series' DICOM window (SeriesRecord::window_center/width, where pictures start) on every backend:
// stored and read back, replaced with the series, refused when it is not a window; and a SQLite file
// of the schema before it migrated keeping its series, with no window.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "db/sqlite/schema_migrations.h"
#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_series;

NewSeries windowed(double centre, double width) {
  NewSeries s = new_series("P1", "1.2.3", "1.2.3.4", 1.0f);
  s.series.window_center = centre;
  s.series.window_width = width;
  return s;
}

template <typename Backend>
class StoreSeriesWindow : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreSeriesWindow, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreSeriesWindow, TheWindowRoundTripsAndIsReplacedWithTheSeries) {
  Store* store = this->store_.get();
  ASSERT_TRUE(store->put_series(windowed(-600.5, 1600.25)).ok());
  auto got = store->get_series("1.2.3.4");
  ASSERT_TRUE(got.ok()) << got.status().to_string();
  EXPECT_EQ(got->window_center, -600.5);
  EXPECT_EQ(got->window_width, 1600.25);
  ASSERT_TRUE(store->put_series(windowed(40, 400)).ok());
  got = store->get_series("1.2.3.4");
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->window_center, 40);
  EXPECT_EQ(got->window_width, 400);
  ASSERT_TRUE(store->put_series(new_series("P1", "1.2.3", "1.2.3.5", 2.0f)).ok());
  got = store->get_series("1.2.3.5");
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->window_width, 0);  // none
}

TYPED_TEST(StoreSeriesWindow, AWindowThatIsNoneIsRefusedAndNothingIsStored) {
  Store* store = this->store_.get();
  for (const auto& [centre, width] : {std::pair{40.0, -1.0}, {NAN, 400.0}, {40.0, INFINITY}}) {
    const Status s = store->put_series(windowed(centre, width)).status();
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << s.to_string();
    EXPECT_NE(s.message().find("series window"), std::string::npos) << s.message();
    EXPECT_EQ(store->get_series("1.2.3.4").status().code(), StatusCode::kNotFound);
  }
}

TEST(SqliteStoreSeriesWindow, AFileOfSchemaNineIsMigratedKeepingItsSeriesWithoutAWindow) {
  testing::TempDir dir;
  const std::string path = dir.file("v9.db");
  {
    auto store = testing::open_store(path);
    ASSERT_TRUE(store->put_series(windowed(40, 400)).ok());
  }
  testing::exec_sql(path, std::string(testing::kBackToSchemaV9) + "PRAGMA user_version = 9");
  auto store = testing::open_store(path);
  ASSERT_TRUE(store);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
  auto got = store->get_series("1.2.3.4");
  ASSERT_TRUE(got.ok()) << got.status().to_string();
  EXPECT_EQ(got->window_width, 0);
  EXPECT_EQ(got->geometry.dims[0], windowed(0, 0).series.geometry.dims[0]);
}

}  // namespace
}  // namespace soiq::db
