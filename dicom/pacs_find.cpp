#include "dicom/pacs_find.h"

#include <dcmtk/dcmnet/dimse.h>
#include <dcmtk/dcmnet/diutil.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <sstream>

#include "core/base/field_rules.h"
#include "dicom/dcmtk_file.h"
#include "dicom/pacs_association.h"

namespace soiq::dicom {
namespace {

bool is_ascii(const std::string& s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; });
}

Status check_text_key(const std::string& field, const std::string& value, std::size_t max_chars) {
  if (value.size() > max_chars)
    return invalid_argument(field + " has " + std::to_string(value.size()) + " characters; at most " +
                            std::to_string(max_chars) + " are allowed");
  // A backslash separates values in DICOM: "A\B" would become a two-valued key.
  if (value.find('\\') != std::string::npos) return invalid_argument(field + " must not contain a backslash");
  for (const char c : value)
    if (static_cast<unsigned char>(c) < 0x20) return invalid_argument(field + " must not contain control characters");
  return ok_status();
}

// DICOM's date range, by the one rule of dates (core/base/field_rules.h).
Status check_date_range(const std::string& range) { return parse_date_range(range).status().in_field("study_date"); }

std::vector<std::string> split_values(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, '\\');) out.push_back(item);
  return out;
}

Status check_modalities(const std::string& modalities) {
  for (const std::string& m : split_values(modalities)) {
    // CS: 1..16 of upper-case letters, digits, space and underscore.
    const bool ok = !m.empty() && m.size() <= 16 && std::all_of(m.begin(), m.end(), [](char c) {
      return std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_' ||
             c == ' ';
    });
    if (!ok)
      return invalid_argument("modalities '" + modalities +
                              "' must be codes such as CT or MR (upper case), several separated by a backslash");
  }
  return ok_status();
}

Status check_query(const PacsQuery& q) {
  if (q.max_matches == 0) return invalid_argument("max_matches must be at least 1");
  if (q.model == PacsModel::kStudyRoot && q.level == PacsLevel::kPatient)
    return invalid_argument("the Study Root model has no PATIENT level; use the Patient Root model");
  SOIQ_RETURN_IF_ERROR(check_text_key("patient_id", q.patient_id, 64));
  SOIQ_RETURN_IF_ERROR(check_text_key("patient_name", q.patient_name, 64));
  if (q.level == PacsLevel::kPatient) {
    for (const auto& [field, value] : {std::pair{"study_date", &q.study_date},
                                       {"modalities", &q.modalities},
                                       {"study_uid", &q.study_uid},
                                       {"accession_number", &q.accession_number}})
      if (!value->empty()) return invalid_argument(std::string(field) + " is a study key; query at STUDY level");
  }
  if (!q.study_date.empty()) SOIQ_RETURN_IF_ERROR(check_date_range(q.study_date));
  if (!q.modalities.empty()) SOIQ_RETURN_IF_ERROR(check_modalities(q.modalities));
  if (!q.study_uid.empty() &&
      (q.study_uid.size() > 64 || !std::all_of(q.study_uid.begin(), q.study_uid.end(), [](char c) {
         return c == '.' || std::isdigit(static_cast<unsigned char>(c));
       })))
    return invalid_argument("study_uid '" + q.study_uid + "' must be at most 64 digits and dots");
  SOIQ_RETURN_IF_ERROR(check_text_key("accession_number", q.accession_number, 16));
  return ok_status();
}

DcmDataset query_keys(const PacsQuery& q) {
  DcmDataset keys;
  if (!is_ascii(q.patient_id) || !is_ascii(q.patient_name))
    keys.putAndInsertString(DCM_SpecificCharacterSet, "ISO_IR 192");
  const bool study = q.level == PacsLevel::kStudy;
  keys.putAndInsertString(DCM_QueryRetrieveLevel, study ? "STUDY" : "PATIENT");
  // Empty keys are return keys (universal matching): the PACS fills them in each match.
  keys.putAndInsertString(DCM_PatientID, q.patient_id.c_str());
  keys.putAndInsertString(DCM_PatientName, q.patient_name.c_str());
  keys.putAndInsertString(DCM_PatientSex, "");
  keys.putAndInsertString(DCM_PatientBirthDate, "");
  if (study) {
    keys.putAndInsertString(DCM_StudyInstanceUID, q.study_uid.c_str());
    keys.putAndInsertString(DCM_StudyDate, q.study_date.c_str());
    keys.putAndInsertString(DCM_StudyDescription, "");
    keys.putAndInsertString(DCM_ModalitiesInStudy, q.modalities.c_str());
    keys.putAndInsertString(DCM_AccessionNumber, q.accession_number.c_str());
    keys.putAndInsertString(DCM_NumberOfStudyRelatedInstances, "");
  }
  return keys;
}

PacsMatch to_match(DcmDataset& ds) {
  // Convert to UTF-8 when the PACS says its values are in another character set; if DCMTK
  // cannot (no converter for it), the bytes stay as sent.
  if (!get_string(ds, DCM_SpecificCharacterSet).empty()) (void)ds.convertToUTF8();
  PacsMatch m;
  m.patient_id = get_string(ds, DCM_PatientID);
  m.patient_name = get_string(ds, DCM_PatientName);
  m.patient_sex = get_string(ds, DCM_PatientSex);
  m.patient_birth_date = get_string(ds, DCM_PatientBirthDate);
  m.study_uid = get_string(ds, DCM_StudyInstanceUID);
  m.study_date = get_string(ds, DCM_StudyDate);
  m.study_description = get_string(ds, DCM_StudyDescription);
  m.modalities = get_string_array(ds, DCM_ModalitiesInStudy);
  m.accession_number = get_string(ds, DCM_AccessionNumber);
  if (const auto n = get_number(ds, DCM_NumberOfStudyRelatedInstances)) m.number_of_instances = static_cast<int>(*n);
  return m;
}

// Collects the matches as they arrive so that a PACS with too many can be stopped early.
class FindScu : public DcmSCU {
 public:
  explicit FindScu(std::size_t max_matches) : max_matches_(max_matches) {}

  OFCondition handleFINDResponse(const T_ASC_PresentationContextID, QRResponse* response,
                                 OFBool& wait_for_next) override {
    wait_for_next = OFFalse;
    if (response == nullptr) return DIMSE_NULLKEY;
    if (!DICOM_PENDING_STATUS(response->m_status)) {
      final_status_ = response->m_status;
      return EC_Normal;
    }
    if (response->m_dataset != nullptr) matches_.push_back(to_match(*response->m_dataset));
    if (matches_.size() > max_matches_) {
      overflow_ = true;  // stop reading; the caller aborts the association, which ends the query
      return EC_Normal;
    }
    wait_for_next = OFTrue;
    return EC_Normal;
  }

  std::vector<PacsMatch> matches_;
  std::optional<Uint16> final_status_;
  bool overflow_ = false;

 private:
  std::size_t max_matches_;
};

bool has_any(const std::string& listed, const std::vector<std::string>& wanted) {
  for (const std::string& m : split_values(listed))
    if (std::find(wanted.begin(), wanted.end(), m) != wanted.end()) return true;
  return false;
}

}  // namespace

Result<std::vector<PacsMatch>> pacs_find(const PacsPeer& peer, const PacsQuery& query) {
  SOIQ_RETURN_IF_ERROR(validate_pacs_peer(peer));
  SOIQ_RETURN_IF_ERROR(check_query(query));
  const char* model = query.model == PacsModel::kPatientRoot ? UID_FINDPatientRootQueryRetrieveInformationModel
                                                             : UID_FINDStudyRootQueryRetrieveInformationModel;
  const std::string model_name = query.model == PacsModel::kPatientRoot ? "Patient Root" : "Study Root";
  const std::string service = "C-FIND (" + model_name + ")";

  FindScu scu(query.max_matches);
  configure_scu(scu, peer);
  scu.addPresentationContext(model, uncompressed_transfer_syntaxes());
  SOIQ_RETURN_IF_ERROR(open_association(scu, peer, service));
  const T_ASC_PresentationContextID pcid = scu.findAnyPresentationContextID(model, "");
  if (pcid == 0) {
    close_association(scu, /*abort=*/true);
    return failed_precondition(describe_pacs_peer(peer) + " does not offer the " + model_name + " C-FIND model");
  }
  DcmDataset keys = query_keys(query);
  const OFCondition cond = scu.sendFINDRequest(pcid, &keys, nullptr);
  if (scu.overflow_) {
    close_association(scu, /*abort=*/true);
    return resource_exhausted(describe_pacs_peer(peer) + " has more than " + std::to_string(query.max_matches) +
                              " matches for this query; narrow it (patient id, dates) or raise max_matches");
  }
  if (cond.bad() || !scu.final_status_) {
    close_association(scu, /*abort=*/true);
    return association_failure(peer, service, cond.bad() ? cond : DIMSE_BADMESSAGE);
  }
  close_association(scu, /*abort=*/false);
  if (*scu.final_status_ != STATUS_Success)
    return failed_precondition(
        describe_pacs_peer(peer) + " ended the " + service + " with status " + dimse_status_hex(*scu.final_status_) +
        " (" + DU_cfindStatusString(*scu.final_status_) + ")" +
        (*scu.final_status_ == 0xA900 && query.model == PacsModel::kPatientRoot ? "; try the Study Root model" : ""));

  std::vector<PacsMatch> matches = std::move(scu.matches_);
  if (!query.modalities.empty()) {
    const std::vector<std::string> wanted = split_values(query.modalities);
    for (const PacsMatch& m : matches)
      if (m.modalities.empty())
        return failed_precondition(describe_pacs_peer(peer) +
                                   " ignores Modalities in Study (0008,0061): it returned study '" + m.study_uid +
                                   "' without it, so the modality filter cannot be trusted; query without modalities");
    // A PACS that returns the key but matched loosely: keep only what was asked for.
    matches.erase(std::remove_if(matches.begin(), matches.end(),
                                 [&](const PacsMatch& m) { return !has_any(m.modalities, wanted); }),
                  matches.end());
  }
  return matches;
}

}  // namespace soiq::dicom
