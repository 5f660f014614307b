#include "db/sqlite/sqlite_records.h"

namespace soiq::db {

std::string select_sql(std::initializer_list<std::string_view> column_lists,
                       std::initializer_list<std::string_view> rest) {
  std::string sql = "SELECT ";
  const char* separator = "";
  for (std::string_view columns : column_lists) {
    sql.append(separator).append(columns);
    separator = ", ";
  }
  for (std::string_view part : rest) sql.append(" ").append(part);
  return sql;
}

std::string join_uid_list(const std::vector<std::string>& uids) {
  std::string out;
  for (size_t i = 0; i < uids.size(); ++i) {
    if (i) out += '\\';
    out += uids[i];
  }
  return out;
}

std::vector<std::string> split_uid_list(const std::string& joined) {
  std::vector<std::string> out;
  if (joined.empty()) return out;
  size_t start = 0;
  while (true) {
    const size_t end = joined.find('\\', start);
    out.push_back(joined.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return out;
    start = end + 1;
  }
}

PatientRecord read_patient(const Statement& row, int col) {
  PatientRecord p;
  p.patient_id = row.text(col);
  p.sex = row.text(col + 1);
  p.birth_date = row.text(col + 2);
  p.study_count = row.int64(col + 3);
  p.structure_count = row.int64(col + 4);
  return p;
}

StudyRecord read_study(const Statement& row, int col) {
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

StructureRecord read_structure(const Statement& row, int col) {
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

SeriesRecord read_series(const Statement& row, int col) {
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
  return s;
}

}  // namespace soiq::db
