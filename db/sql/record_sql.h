#pragma once
// The SELECT column lists of the store's records and the code that reads a row back into a record,
// shared by every query that returns records in both backends (the SQL is the same in SQLite's and
// PostgreSQL's dialect). Each list assumes the aliases of kStructureFrom: s = structures,
// st = studies, p = patients, sf = surfaces.

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "db/store.h"

namespace soiq::db {

// The FROM clause of a query over structures with their study, patient and surface.
inline constexpr char kStructureFrom[] = R"sql(
  FROM structures s
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  JOIN surfaces sf ON sf.sha256 = s.surface_sha256)sql";

// PatientRecord with its counts; needs p.
inline constexpr char kPatientColumns[] = R"sql(
  p.patient_id, p.sex, p.birth_date,
  (SELECT count(*) FROM studies c WHERE c.patient_pk = p.pk),
  (SELECT count(*) FROM studies c JOIN structures cs ON cs.study_pk = c.pk WHERE c.patient_pk = p.pk),
  p.patient_name)sql";
inline constexpr int kPatientColumnCount = 6;

// StudyRecord with its structure count; needs st and p.
inline constexpr char kStudyColumns[] = R"sql(
  st.study_uid, p.patient_id, st.study_date, st.description, st.modality, st.age_years,
  (SELECT count(*) FROM structures cs WHERE cs.study_pk = st.pk), st.study_time, st.study_id,
  st.accession_number)sql";
inline constexpr int kStudyColumnCount = 10;

// StructureRecord with its SurfaceInfo; needs s, st, p, sf.
inline constexpr char kStructureColumns[] = R"sql(
  s.id, p.patient_id, st.study_uid, s.name, s.laterality, s.robust, s.created_at, sf.sha256,
  sf.vertex_count, sf.triangle_count, sf.min_x, sf.min_y, sf.min_z, sf.max_x, sf.max_y, sf.max_z,
  s.source_series_uid, s.source_uid, s.surface_area_bound_mm2, s.surface_perimeter_bound_mm)sql";
inline constexpr int kStructureColumnCount = 20;

// SeriesRecord; needs se = series and st.
inline constexpr char kSeriesColumns[] = R"sql(
  se.series_uid, st.study_uid, se.modality, se.origin_x, se.origin_y, se.origin_z, se.spacing_x,
  se.spacing_y, se.spacing_z, se.dim_x, se.dim_y, se.dim_z, se.d00, se.d01, se.d02, se.d10, se.d11,
  se.d12, se.d20, se.d21, se.d22, se.image_sha256, se.frame_of_reference_uid, se.sop_class_uid,
  se.slice_instance_uids, se.series_number, se.description, se.window_center, se.window_width,
  se.slice_positions)sql";
inline constexpr int kSeriesColumnCount = 30;

// The row count of each table, in the order of Counts' fields; the instances' apart (a store of an
// older schema, opened read only, has no instance tables).
inline constexpr char kCountsSql[] = R"sql(
  SELECT (SELECT count(*) FROM patients),
         (SELECT count(*) FROM studies),
         (SELECT count(*) FROM series),
         (SELECT count(*) FROM structures),
         (SELECT count(*) FROM surfaces),
         (SELECT count(*) FROM feature_cache),
         (SELECT count(*) FROM precompute_queue WHERE failure = ''),
         (SELECT count(*) FROM precompute_queue WHERE failure <> ''))sql";

// Counts::instances, instance_files and instance_bytes. length() of a blob reads its size, not its
// bytes, in both engines.
inline constexpr char kInstanceCountsSql[] = R"sql(
  SELECT (SELECT count(*) FROM instances),
         (SELECT count(*) FROM instance_files),
         (SELECT coalesce(sum(length(blob)), 0) FROM instance_files))sql";

// The distinct modalities of the series, by a skip-scan over the series_modality index: one index
// seek per distinct value, not a pass over every series (neither engine skips by itself).
inline constexpr char kSeriesModalitiesSql[] = R"sql(
  WITH RECURSIVE m(modality) AS (
    SELECT min(modality) FROM series
    UNION ALL
    SELECT (SELECT min(modality) FROM series WHERE modality > m.modality) FROM m WHERE m.modality IS NOT NULL)
  SELECT modality FROM m WHERE modality IS NOT NULL)sql";

// The SQL of a query returning records: "SELECT", the column lists above separated by commas,
// then the parts of the rest (FROM onwards) separated by spaces. Only the column lists and the
// clauses vary between the store's record queries, so each query names just those.
std::string select_sql(std::initializer_list<std::string_view> column_lists,
                       std::initializer_list<std::string_view> rest);

// The parameters of an IN list of n values: "?1, ?2, …, ?n".
std::string parameter_list(size_t n);

// A PostgreSQL array literal of `values` as one text parameter: '{1,2}' for a bigint[], '{"a","b"}'
// (every element quoted and escaped) for a text[] or, with hex bytea elements, a bytea[].
std::string array_literal(const std::vector<int64_t>& values);
std::string array_literal(const std::vector<std::string>& values);

// A list of UIDs as one column: joined with '\\' (DICOM's value separator; no UID contains it).
std::string join_uid_list(const std::vector<std::string>& uids);
std::vector<std::string> split_uid_list(const std::string& joined);  // "" -> {}

// An unevenly spaced series' slice positions (ImageGeometry::slice_positions_mm) as one column:
// %.17g each (exact), space-separated; "" for every evenly spaced one. A value that does not
// parse ends the list, which validate_geometry then refuses (one per slice).
std::string join_positions(const std::vector<double>& positions);
std::vector<double> split_positions(const std::string& joined);

// Each reads its columns starting at `col` from a row with text, int64, real and optional_real by
// column: a SQLite statement (sqlite_statement.h) or a PostgreSQL result's row (PgRow).
template <typename Row>
PatientRecord read_patient(const Row& row, int col) {
  PatientRecord p;
  p.patient_id = row.text(col);
  p.sex = row.text(col + 1);
  p.birth_date = row.text(col + 2);
  p.study_count = row.int64(col + 3);
  p.structure_count = row.int64(col + 4);
  p.patient_name = row.text(col + 5);
  return p;
}

template <typename Row>
StudyRecord read_study(const Row& row, int col) {
  StudyRecord s;
  s.study_uid = row.text(col);
  s.patient_id = row.text(col + 1);
  s.study_date = row.text(col + 2);
  s.description = row.text(col + 3);
  s.modality = row.text(col + 4);
  s.age_years = row.optional_real(col + 5);
  s.structure_count = row.int64(col + 6);
  s.study_time = row.text(col + 7);
  s.study_id = row.text(col + 8);
  s.accession_number = row.text(col + 9);
  return s;
}

template <typename Row>
StructureRecord read_structure(const Row& row, int col) {
  StructureRecord s;
  s.id = row.int64(col);
  s.patient_id = row.text(col + 1);
  s.study_uid = row.text(col + 2);
  s.name = row.text(col + 3);
  s.laterality = row.text(col + 4);
  s.robust = row.int64(col + 5) != 0;
  s.created_at = row.text(col + 6);
  s.surface.sha256 = row.text(col + 7);
  s.surface.vertex_count = row.int64(col + 8);
  s.surface.triangle_count = row.int64(col + 9);
  for (int i = 0; i < 6; ++i) s.surface.bounds_mm[i] = row.real(col + 10 + i);
  s.source_series_uid = row.text(col + 16);
  s.source_uid = row.text(col + 17);
  s.surface.area_bound_mm2 = row.real(col + 18);
  s.surface.perimeter_bound_mm = row.real(col + 19);
  return s;
}

template <typename Row>
SeriesRecord read_series(const Row& row, int col) {
  SeriesRecord s;
  s.series_uid = row.text(col);
  s.study_uid = row.text(col + 1);
  s.modality = row.text(col + 2);
  for (int a = 0; a < 3; ++a) {
    s.geometry.origin_mm[a] = row.real(col + 3 + a);
    s.geometry.spacing_mm[a] = row.real(col + 6 + a);
    s.geometry.dims[a] = row.int64(col + 9 + a);
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) s.geometry.direction[r][c] = row.real(col + 12 + 3 * r + c);
  }
  s.sha256 = row.text(col + 21);
  s.frame_of_reference_uid = row.text(col + 22);
  s.sop_class_uid = row.text(col + 23);
  s.slice_instance_uids = split_uid_list(row.text(col + 24));
  s.series_number = row.int64(col + 25);
  s.description = row.text(col + 26);
  s.window_center = row.real(col + 27);
  s.window_width = row.real(col + 28);
  s.geometry.slice_positions_mm = split_positions(row.text(col + 29));
  return s;
}

}  // namespace soiq::db
