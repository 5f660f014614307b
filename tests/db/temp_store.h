#pragma once
// Test support for tests/db: the temporary directory of tests/support, and small builders of
// valid store inputs.

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <random>
#include <string>

#include "db/image_blob.h"
#include "db/sqlite/sqlite_store.h"
#include "db/surface_blob.h"
#include "tests/support/temp_dir.h"

namespace soiq::db::testing {

using soiq::testing::TempDir;

inline std::unique_ptr<SqliteStore> open_store(const std::string& path, SqliteOptions options = {}) {
  auto store = SqliteStore::open(path, options);
  EXPECT_TRUE(store.ok()) << store.status().to_string();
  return store.ok() ? std::move(store).value() : nullptr;
}

// A tetrahedron shifted by `offset`: distinct offsets give distinct surfaces.
inline TriangleMesh tetrahedron(double offset) {
  TriangleMesh m;
  m.vertices_mm = {{offset, 0, 0}, {offset + 1, 0, 0}, {offset, 1, 0}, {offset, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

// The SQL that takes a store of the latest schema back to version 12's tables, to version 11's, 10's,
// 9's, 7's, 6's, 4's and 3's, for the tests of older files' migration (each test then drops what its own
// older version lacked too).
#define SOIQ_BACK_TO_SCHEMA_V12 "ALTER TABLE stored_features DROP COLUMN precomputed_set; "
inline constexpr char kBackToSchemaV12[] = SOIQ_BACK_TO_SCHEMA_V12;
#define SOIQ_BACK_TO_SCHEMA_V11 SOIQ_BACK_TO_SCHEMA_V12 "ALTER TABLE series DROP COLUMN slice_positions; "
inline constexpr char kBackToSchemaV11[] = SOIQ_BACK_TO_SCHEMA_V11;
#define SOIQ_BACK_TO_SCHEMA_V10 SOIQ_BACK_TO_SCHEMA_V11 "DROP TABLE instances; DROP TABLE instance_files; "
inline constexpr char kBackToSchemaV10[] = SOIQ_BACK_TO_SCHEMA_V10;
#define SOIQ_BACK_TO_SCHEMA_V9 \
  SOIQ_BACK_TO_SCHEMA_V10      \
  "ALTER TABLE series DROP COLUMN window_center; ALTER TABLE series DROP COLUMN window_width; "
inline constexpr char kBackToSchemaV9[] = SOIQ_BACK_TO_SCHEMA_V9;
#define SOIQ_BACK_TO_SCHEMA_V7                                                      \
  SOIQ_BACK_TO_SCHEMA_V9                                                            \
  "DROP INDEX patients_name_lower; ALTER TABLE patients DROP COLUMN patient_name; " \
  "ALTER TABLE series DROP COLUMN series_number; ALTER TABLE series DROP COLUMN description; "
inline constexpr char kBackToSchemaV7[] = SOIQ_BACK_TO_SCHEMA_V7;
#define SOIQ_BACK_TO_SCHEMA_V6 SOIQ_BACK_TO_SCHEMA_V7 "DROP TABLE stage2_work; DROP TABLE replicas; "
inline constexpr char kBackToSchemaV6[] = SOIQ_BACK_TO_SCHEMA_V6;
#define SOIQ_BACK_TO_SCHEMA_V4                                                                                  \
  SOIQ_BACK_TO_SCHEMA_V6                                                                                        \
  "DROP TABLE precompute_queue; DROP TABLE stored_features; "                                                   \
  "DROP INDEX stage1_rows_features_unstored; DROP INDEX stage1_rows_voxel_volume_mm3; "                         \
  "DROP INDEX stage1_rows_surface_area_mm2; DROP INDEX stage1_rows_sphericity; "                                \
  "DROP INDEX stage1_rows_elongation; DROP INDEX stage1_rows_flatness; "                                        \
  "DROP INDEX stage1_rows_maximum_3d_diameter_mm; "                                                             \
  "ALTER TABLE stage1_rows DROP COLUMN features_stored; ALTER TABLE stage1_rows DROP COLUMN voxel_volume_mm3; " \
  "ALTER TABLE stage1_rows DROP COLUMN surface_area_mm2; ALTER TABLE stage1_rows DROP COLUMN sphericity; "      \
  "ALTER TABLE stage1_rows DROP COLUMN elongation; ALTER TABLE stage1_rows DROP COLUMN flatness; "              \
  "ALTER TABLE stage1_rows DROP COLUMN maximum_3d_diameter_mm; "
inline constexpr char kBackToSchemaV4[] = SOIQ_BACK_TO_SCHEMA_V4;
inline constexpr char kBackToSchemaV3[] = SOIQ_BACK_TO_SCHEMA_V4
    "ALTER TABLE structures DROP COLUMN surface_perimeter_bound_mm; "
    "ALTER TABLE structures DROP COLUMN surface_area_bound_mm2; ";
#undef SOIQ_BACK_TO_SCHEMA_V12
#undef SOIQ_BACK_TO_SCHEMA_V11
#undef SOIQ_BACK_TO_SCHEMA_V4
#undef SOIQ_BACK_TO_SCHEMA_V6
#undef SOIQ_BACK_TO_SCHEMA_V7
#undef SOIQ_BACK_TO_SCHEMA_V9
#undef SOIQ_BACK_TO_SCHEMA_V10

inline NewStructure new_structure(const std::string& patient_id, const std::string& study_uid, const std::string& name,
                                  double surface_offset = 0) {
  NewStructure s;
  s.patient.patient_id = patient_id;
  s.study.study_uid = study_uid;
  s.name = name;
  auto encoded = encode_surface(tetrahedron(surface_offset));
  EXPECT_TRUE(encoded.ok());
  s.surface = encoded->info;
  s.surface_blob = encoded->blob;
  return s;
}

inline NewSeries new_series(const std::string& patient_id, const std::string& study_uid, const std::string& series_uid,
                            float fill) {
  NewSeries s;
  s.patient.patient_id = patient_id;
  s.study.study_uid = study_uid;
  s.series.series_uid = series_uid;
  s.series.modality = "MR";
  Image image;
  image.geometry.dims = {3, 2, 2};
  image.geometry.spacing_mm = {0.5, 0.75, 2};
  image.geometry.origin_mm = {-10, 20, 30.25};
  image.voxels.assign(12, fill);
  s.series.geometry = image.geometry;
  auto encoded = encode_image(image);
  EXPECT_TRUE(encoded.ok());
  s.series.sha256 = encoded->sha256;
  s.image_blob = encoded->blob;
  return s;
}

// Runs `sql` on the SQLite file itself, as another program or an older soiqd would; an error fails
// the test.
inline void exec_sql(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace soiq::db::testing
