#include "server/app/structures_on_series.h"

#include <set>

namespace soiq::server {

std::string structure_named(const db::StructureRecord& s) {
  return "structure " + std::to_string(s.id) + " ('" + s.name + "')";
}

Result<StructuresOnSeries> structures_on_series(db::Store& store, const std::vector<int64_t>& ids, int max_structures,
                                                const std::string& object) {
  if (ids.empty()) return invalid_argument("no structure ids given: name the structures to put in the " + object);
  if (ids.size() > size_t(max_structures))
    return invalid_argument(std::to_string(ids.size()) + " structures asked; one " + object + " holds at most " +
                            std::to_string(max_structures));
  StructuresOnSeries out;
  std::set<int64_t> seen;
  for (int64_t id : ids) {
    if (!seen.insert(id).second) return invalid_argument("structure " + std::to_string(id) + " is named twice");
    SOIQ_ASSIGN_OR_RETURN(db::StructureRecord s, store.get_structure(id));
    if (s.source_series_uid.empty())
      return failed_precondition(structure_named(s) +
                                 " was uploaded as a surface, not imported from DICOM, so there "
                                 "are no DICOM images for an " +
                                 object +
                                 " to reference; import the images and the RT Structure Set with 'soiq import' and "
                                 "export that structure");
    const auto& structures = out.structures;
    if (!structures.empty() && s.source_series_uid != structures.front().source_series_uid)
      return invalid_argument(structure_named(structures.front()) + " is on series " +
                              structures.front().source_series_uid + " but " + structure_named(s) + " is on series " +
                              s.source_series_uid + "; one " + object +
                              " references one series: export them separately");
    out.structures.push_back(std::move(s));
  }
  const db::StructureRecord& first = out.structures.front();
  Result<db::SeriesRecord> series = store.get_series(first.source_series_uid);
  if (!series.ok() && series.status().code() == StatusCode::kNotFound)
    return not_found("the image series " + first.source_series_uid + " that " + structure_named(first) +
                     " was imported on is no longer stored; import it again");
  SOIQ_RETURN_IF_ERROR(series.status());
  if (series->frame_of_reference_uid.empty() || series->sop_class_uid.empty() ||
      series->slice_instance_uids.size() != size_t(series->geometry.dims[2]))
    return failed_precondition("series " + series->series_uid +
                               " was stored without its DICOM references (frame of reference, slice SOP instances); "
                               "import its files again with 'soiq import' to export an " +
                               object + " on it");
  SOIQ_ASSIGN_OR_RETURN(const db::StudyRecord study, store.get_study(series->study_uid));
  SOIQ_ASSIGN_OR_RETURN(const db::PatientRecord patient, store.get_patient(study.patient_id));
  dicom::SegSource& source = out.source;
  source.patient_id = patient.patient_id;
  source.patient_name = patient.patient_name;  // "" unless soiqd keeps names
  source.patient_sex = patient.sex;
  source.patient_birth_date = patient.birth_date;
  source.study_uid = study.study_uid;
  source.study_date = study.study_date;
  source.study_time = study.study_time;
  source.study_id = study.study_id;
  source.accession_number = study.accession_number;
  source.series_uid = series->series_uid;
  source.frame_of_reference_uid = series->frame_of_reference_uid;
  source.modality = series->modality;
  source.sop_class_uid = series->sop_class_uid;
  source.slice_sop_instance_uids = series->slice_instance_uids;
  source.geometry = series->geometry;
  return out;
}

}  // namespace soiq::server
