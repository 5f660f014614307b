#include "client/cli/show_records.h"

#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace soiq::cli {

namespace {

std::string g(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

void line(const char* key, const std::string& value) { std::printf("%-22s %s\n", key, value.c_str()); }

}  // namespace

std::string geometry_text(const soiq::v1::ImageGeometry& geo) {
  if (geo.dims_size() != 3 || geo.spacing_size() != 3) return "no geometry";
  return std::to_string(geo.dims(0)) + "x" + std::to_string(geo.dims(1)) + "x" + std::to_string(geo.dims(2)) +
         " voxels of " + g(geo.spacing(0)) + "x" + g(geo.spacing(1)) + "x" + g(geo.spacing(2)) + " mm" +
         geometry_notes(geo);
}

std::string geometry_notes(const soiq::v1::ImageGeometry& geo) {
  std::string out;
  if (geo.slice_positions_size() > 0) out += ", slices unevenly spaced";
  if (geo.direction_size() != 9) return out;
  // The angle between k and the normal of the slices (i x j).
  const double i[3] = {geo.direction(0), geo.direction(3), geo.direction(6)};
  const double j[3] = {geo.direction(1), geo.direction(4), geo.direction(7)};
  const double k[3] = {geo.direction(2), geo.direction(5), geo.direction(8)};
  const double n[3] = {i[1] * j[2] - i[2] * j[1], i[2] * j[0] - i[0] * j[2], i[0] * j[1] - i[1] * j[0]};
  const double c = std::abs(n[0] * k[0] + n[1] * k[1] + n[2] * k[2]);
  const double degrees = std::acos(std::min(1.0, c)) * 180 / std::numbers::pi;
  if (degrees > 0.01) out += ", tilted " + g(degrees) + " degrees";
  return out;
}

std::string record_json(const google::protobuf::Message& message) {
  std::string out;
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  if (!google::protobuf::util::MessageToJsonString(message, &out, options).ok()) return "{}";
  return out;
}

void print_patient(const soiq::v1::Patient& p) {
  line("patient_id", p.patient_id());
  line("sex", p.sex());
  line("birth_date", p.birth_date());
  line("studies", std::to_string(p.study_count()));
  line("structures", std::to_string(p.structure_count()));
}

void print_study(const soiq::v1::Study& s) {
  line("study_uid", s.study_uid());
  line("patient_id", s.patient_id());
  line("study_date", s.study_date());
  line("description", s.description());
  line("modality", s.modality());
  line("age_years", s.has_age_years() ? g(s.age_years()) : "");
  line("structures", std::to_string(s.structure_count()));
  for (const soiq::v1::Series& series : s.series()) {
    line("series", series.series_uid() + " " + series.modality() + ", " + geometry_text(series.geometry()));
  }
}

void print_structure(const soiq::v1::Structure& s) {
  line("id", std::to_string(s.id()));
  line("name", s.name());
  line("laterality", s.laterality());
  line("patient_id", s.patient_id());
  line("study_uid", s.study_uid());
  line("vertices", std::to_string(s.vertex_count()));
  line("triangles", std::to_string(s.triangle_count()));
  std::string bounds;
  for (int i = 0; i < s.bounds_mm_size(); ++i) {
    if (i) bounds += ' ';
    bounds += g(s.bounds_mm(i));
  }
  line("bounds_mm", bounds);
  line("robust", s.robust() ? "yes" : "no");
  line("surface_sha256", s.surface_sha256());
  line("created_at", s.created_at());
}

void print_server_info(const soiq::v1::ServerInfo& i) {
  line("version", i.version());
  line("feature_definitions", std::to_string(i.feature_definition_version()));
  line("features", std::to_string(i.features_size()) + " (soiq info --features lists them)");
  line("patients", std::to_string(i.patients()));
  line("studies", std::to_string(i.studies()));
  line("series", std::to_string(i.series()));
  std::string modalities;
  for (const std::string& m : i.series_modalities()) modalities += (modalities.empty() ? "" : " ") + m;
  line("series_modalities", modalities.empty() ? "none" : modalities);
  line("structures", std::to_string(i.structures()));
  line("surfaces", std::to_string(i.surfaces()));
  line("cached_features", std::to_string(i.cached_features()));
  line("dicom_instances", std::to_string(i.instances()) + " in " + std::to_string(i.instance_files()) + " files, " +
                              std::to_string(i.instance_bytes()) + " bytes" +
                              (i.keep_instances() ? "" : " (imports keep none: soiqd --keep-instances off)"));
  line("precompute", !i.precompute_enabled() ? "off (soiqd --precompute on)"
                                             : std::to_string(i.precompute_queued()) + " queued, " +
                                                   std::to_string(i.precompute_failed()) + " failed");
  line("max_upload_bytes", std::to_string(i.max_upload_bytes()));
  line("max_grid_voxels", std::to_string(i.max_grid_voxels()));
  line("max_conversions", std::to_string(i.max_concurrent_conversions()));
  line("memory_budget_bytes", std::to_string(i.memory_budget_bytes()));
  line("memory_in_use_bytes", std::to_string(i.memory_in_use_bytes()));
  line("memory_peak_bytes", std::to_string(i.memory_peak_bytes()));
  line("pacs", i.pacs().empty() ? "none (soiqd --pacs AE@HOST:PORT)" : i.pacs());
  line("query_result_cap", std::to_string(i.query_result_cap()));
  line("stage1_cap", std::to_string(i.stage1_cap()));
  line("max_id_bytes", std::to_string(i.max_id_bytes()));
  line("max_name_bytes", std::to_string(i.max_name_bytes()));
}

std::vector<std::string> patient_columns() { return {"patient_id", "sex", "birth_date", "studies", "structures"}; }

std::vector<Cell> patient_cells(const soiq::v1::Patient& p) {
  return {text_cell(p.patient_id()), text_cell(p.sex()), text_cell(p.birth_date()), int_cell(p.study_count()),
          int_cell(p.structure_count())};
}

std::vector<std::string> study_columns() {
  return {"study_uid", "patient_id", "study_date", "modality", "age_years", "series", "structures", "description"};
}

std::vector<Cell> study_cells(const soiq::v1::Study& s) {
  return {text_cell(s.study_uid()),
          text_cell(s.patient_id()),
          text_cell(s.study_date()),
          text_cell(s.modality()),
          s.has_age_years() ? number_cell(s.age_years()) : Cell{"", "null"},
          int_cell(s.series_size()),
          int_cell(s.structure_count()),
          text_cell(s.description())};
}

std::vector<std::string> structure_columns() {
  return {"id", "patient_id", "study_uid", "name", "laterality", "triangles", "robust"};
}

std::vector<Cell> structure_cells(const soiq::v1::Structure& s) {
  return {int_cell(s.id()),
          text_cell(s.patient_id()),
          text_cell(s.study_uid()),
          text_cell(s.name()),
          text_cell(s.laterality()),
          int_cell(s.triangle_count()),
          Cell{s.robust() ? "yes" : "no", s.robust() ? "true" : "false"}};
}

}  // namespace soiq::cli
