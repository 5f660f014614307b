#include "server/api/proto_records.h"

#include "core/base/field_rules.h"

namespace soiq::server {

v1::Patient to_proto(const db::PatientRecord& r) {
  v1::Patient p;
  p.set_patient_id(r.patient_id);
  p.set_sex(r.sex);
  p.set_birth_date(r.birth_date);
  p.set_study_count(r.study_count);
  p.set_structure_count(r.structure_count);
  return p;
}

v1::Study to_proto(const db::StudyRecord& r) {
  v1::Study s;
  s.set_study_uid(r.study_uid);
  s.set_patient_id(r.patient_id);
  s.set_study_date(r.study_date);
  s.set_description(r.description);
  s.set_modality(r.modality);
  if (r.age_years) s.set_age_years(*r.age_years);
  s.set_structure_count(r.structure_count);
  return s;
}

v1::ImageGeometry to_proto(const ImageGeometry& g) {
  v1::ImageGeometry p;
  for (int a = 0; a < 3; ++a) {
    p.add_origin(g.origin_mm[a]);
    p.add_spacing(g.spacing_mm[a]);
    p.add_dims(g.dims[a]);
  }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p.add_direction(g.direction[r][c]);
  for (const double z : g.slice_positions_mm) p.add_slice_positions(z);
  return p;
}

v1::Series to_proto(const db::SeriesRecord& r) {
  v1::Series s;
  s.set_series_uid(r.series_uid);
  s.set_study_uid(r.study_uid);
  s.set_modality(r.modality);
  *s.mutable_geometry() = to_proto(r.geometry);
  s.set_sha256(r.sha256);
  s.set_frame_of_reference_uid(r.frame_of_reference_uid);
  s.set_sop_class_uid(r.sop_class_uid);
  s.set_slice_instance_count(int64_t(r.slice_instance_uids.size()));
  return s;
}

v1::Structure to_proto(const db::StructureRecord& r) {
  v1::Structure s;
  s.set_id(r.id);
  s.set_patient_id(r.patient_id);
  s.set_study_uid(r.study_uid);
  s.set_name(r.name);
  s.set_laterality(r.laterality);
  s.set_surface_sha256(r.surface.sha256);
  s.set_vertex_count(r.surface.vertex_count);
  s.set_triangle_count(r.surface.triangle_count);
  for (double b : r.surface.bounds_mm) s.add_bounds_mm(b);
  s.set_robust(r.robust);
  s.set_created_at(r.created_at);
  s.set_source_series_uid(r.source_series_uid);
  s.set_source_uid(r.source_uid);
  return s;
}

v1::ImportDicomResponse to_proto(const DicomImportResult& r) {
  v1::ImportDicomResponse out;
  for (const db::PatientRecord& p : r.patients) *out.add_patients() = to_proto(p);
  for (const db::StudyRecord& s : r.studies) *out.add_studies() = to_proto(s);
  for (const db::SeriesRecord& s : r.series) *out.add_series() = to_proto(s);
  for (const ImportedStructure& s : r.structures) {
    v1::ImportedStructure* p = out.add_structures();
    *p->mutable_structure() = to_proto(s.structure);
    p->set_referenced_series_uid(s.referenced_series_uid);
    p->set_voxel_count(s.voxel_count);
    p->set_replaced(s.replaced);
  }
  for (const ImportProblem& p : r.problems) {
    v1::ImportProblem* q = out.add_problems();
    q->set_path(p.path);
    q->set_code(status_code_name(p.code));
    q->set_message(p.message);
  }
  for (const std::string& path : r.structure_sets_without_structures) out.add_structure_sets_without_structures(path);
  out.set_files_received(r.files_received);
  out.set_dicom_files_read(r.dicom_files_read);
  out.set_milliseconds(r.milliseconds);
  return out;
}

v1::PacsPullProgress to_proto(const PullProgress& p) {
  v1::PacsPullProgress out;
  out.set_study(p.study);
  out.set_studies(p.studies);
  out.set_received(p.received);
  out.set_remaining(p.remaining);
  return out;
}

v1::FeatureInfo to_proto(const FeatureDef& f) {
  v1::FeatureInfo out;
  out.set_name(std::string(f.name));
  out.set_family(std::string(family_name(f.family)));
  out.set_unit(std::string(f.unit));
  out.set_needs(feature_needs(f));
  out.set_summary(std::string(f.summary));
  out.set_version(f.version);
  out.set_components(f.components);
  return out;
}

Result<db::PatientRecord> from_proto(const v1::Patient& p) {
  SOIQ_RETURN_IF_ERROR(check_id(p.patient_id()).in_field("patient.patient_id"));
  SOIQ_RETURN_IF_ERROR(check_sex(p.sex()).in_field("patient.sex"));
  SOIQ_RETURN_IF_ERROR(check_date(p.birth_date()).in_field("patient.birth_date"));
  db::PatientRecord r;
  r.patient_id = p.patient_id();
  r.sex = p.sex();
  r.birth_date = p.birth_date();
  return r;
}

Result<db::StudyRecord> from_proto(const v1::Study& s, const std::string& patient_id) {
  SOIQ_RETURN_IF_ERROR(check_id(s.study_uid()).in_field("study.study_uid"));
  if (!s.patient_id().empty() && s.patient_id() != patient_id)
    return invalid_argument("'" + s.patient_id() + "' differs from patient.patient_id '" + patient_id + "'")
        .in_field("study.patient_id");
  SOIQ_RETURN_IF_ERROR(check_date(s.study_date()).in_field("study.study_date"));
  SOIQ_RETURN_IF_ERROR(check_text(s.description(), kMaxNameBytes).in_field("study.description"));
  SOIQ_RETURN_IF_ERROR(check_text(s.modality(), kMaxIdBytes).in_field("study.modality"));
  if (s.has_age_years()) SOIQ_RETURN_IF_ERROR(check_age_years(s.age_years()).in_field("study.age_years"));
  db::StudyRecord r;
  r.study_uid = s.study_uid();
  r.patient_id = patient_id;
  r.study_date = s.study_date();
  r.description = s.description();
  r.modality = s.modality();
  if (s.has_age_years()) r.age_years = s.age_years();
  return r;
}

Status check_enum(int value, bool (*is_valid)(int), const char* field) {
  if (is_valid(value)) return ok_status();
  return invalid_argument(std::to_string(value) +
                          " is not a value this server knows (see proto/soiq/v1/soiq.proto for the values)")
      .in_field(field);
}

}  // namespace soiq::server
