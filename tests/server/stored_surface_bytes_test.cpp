// The DownloadSurface engine on its own, without gRPC: a stored box downloads as a file that
// parses back to the same box (in LPS, or mirrored in RAS), and an unknown structure or format is
// refused.
#include "server/app/stored_surface_bytes.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/geometry/mesh_defects.h"
#include "server/app/uploaded_files.h"
#include "tests/db/temp_store.h"
#include "tests/server/stored_box.h"

namespace soiq::server {
namespace {

using db::testing::contains;
using db::testing::TempDir;

class StoredSurfaceBytesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    id_ = testing::add_stored_box(*store_, {1, 2, 3}, {11, 7, 9}, "box");
    ASSERT_GT(id_, 0);
  }

  TempDir tmp_;
  std::unique_ptr<db::SqliteStore> store_ = db::testing::open_store(tmp_.file("soiq.db"));
  MemoryBudget budget_{int64_t(1) << 30};
  FeatureEngine features_{*store_, int64_t(1) << 26, budget_};
  int64_t id_ = 0;
};

TEST_F(StoredSurfaceBytesTest, TheBoxDownloadsAsAnStlThatParsesBackToIt) {
  Result<std::string> bytes = stored_surface_bytes(*store_, features_, id_, "", false);
  ASSERT_TRUE(bytes.ok()) << bytes.status().to_string();
  Result<ParsedSurface> back = parse_surface(*bytes, "stl", false, false, "box");
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  EXPECT_EQ(back->mesh.triangles.size(), 12u);
  EXPECT_NEAR(signed_volume_mm3(back->mesh), 10 * 5 * 6, 1e-9);
}

TEST_F(StoredSurfaceBytesTest, InRasXAndYAreNegated) {
  Result<std::string> bytes = stored_surface_bytes(*store_, features_, id_, "ply", true);
  ASSERT_TRUE(bytes.ok()) << bytes.status().to_string();
  Result<ParsedSurface> as_lps = parse_surface(*bytes, "ply", false, false, "box");
  ASSERT_TRUE(as_lps.ok()) << as_lps.status().to_string();
  double min_x = 1e9, max_y = -1e9;
  for (const Vec3& v : as_lps->mesh.vertices_mm) min_x = std::min(min_x, v[0]), max_y = std::max(max_y, v[1]);
  EXPECT_EQ(min_x, -11);
  EXPECT_EQ(max_y, -2);
}

TEST_F(StoredSurfaceBytesTest, AnUnknownStructureIsNotFound) {
  EXPECT_EQ(stored_surface_bytes(*store_, features_, id_ + 99, "stl", false).status().code(), StatusCode::kNotFound);
}

TEST_F(StoredSurfaceBytesTest, AFormatThatIsOnlyReadIsInvalid) {
  Result<std::string> bytes = stored_surface_bytes(*store_, features_, id_, "off", false);
  EXPECT_EQ(bytes.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(bytes.status().message(), "unknown mesh format 'off'")) << bytes.status().message();
}

}  // namespace
}  // namespace soiq::server
