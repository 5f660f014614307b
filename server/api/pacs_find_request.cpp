#include "server/api/pacs_find_request.h"

#include "server/api/proto_records.h"

namespace soiq::server {

Result<dicom::PacsQuery> pacs_query_of(const v1::PacsFindRequest& r) {
  if (r.max_matches() < 0 || r.max_matches() > kMaxPacsMatches)
    return invalid_argument("max_matches " + std::to_string(r.max_matches()) + " is outside 0.." +
                            std::to_string(kMaxPacsMatches) + " (0: " + std::to_string(kDefaultPacsMatches) + ")");
  SOIQ_RETURN_IF_ERROR(check_enum(r.level(), v1::PacsLevel_IsValid, "level"));
  dicom::PacsQuery q;
  const bool patient_level = r.level() == v1::PACS_LEVEL_PATIENT;
  q.level = patient_level ? dicom::PacsLevel::kPatient : dicom::PacsLevel::kStudy;
  q.model = patient_level ? dicom::PacsModel::kPatientRoot : dicom::PacsModel::kStudyRoot;
  q.patient_id = r.patient_id();
  q.patient_name = r.patient_name();
  q.study_date = r.study_date();
  q.modalities = r.modalities();
  q.study_uid = r.study_uid();
  q.accession_number = r.accession_number();
  q.max_matches = size_t(r.max_matches() == 0 ? kDefaultPacsMatches : r.max_matches());
  return q;
}

v1::PacsMatch to_proto(const dicom::PacsMatch& m) {
  v1::PacsMatch p;
  p.set_patient_id(m.patient_id);
  p.set_patient_name(m.patient_name);
  p.set_patient_sex(m.patient_sex);
  p.set_patient_birth_date(m.patient_birth_date);
  p.set_study_uid(m.study_uid);
  p.set_study_date(m.study_date);
  p.set_study_description(m.study_description);
  p.set_modalities(m.modalities);
  p.set_accession_number(m.accession_number);
  p.set_number_of_instances(m.number_of_instances.value_or(-1));
  return p;
}

}  // namespace soiq::server
