#pragma once
// C-FIND: which patients or studies a PACS holds (docs/DESIGN.md "DICOM and PACS"),
// for the demographics soiq shows before a pull.
//
// Inputs   peer: see pacs_peer.h.
//          query.level: PATIENT or STUDY. query.model: Patient Root (PATIENT or STUDY level) or
//          Study Root (STUDY level only; its patient attributes come with each study).
//          Keys, "" meaning "any": patient_id and patient_name (LO/PN, at most 64 characters,
//          '*' and '?' wildcards, no backslash), and at STUDY level only study_date ("YYYYMMDD",
//          "YYYYMMDD-YYYYMMDD", "YYYYMMDD-", "-YYYYMMDD"; inclusive), modalities ("CT" or
//          "CT\PT": studies with any of them), study_uid (digits and dots), accession_number
//          (at most 16 characters). Matching itself (case, wildcards, ranges) is the PACS's.
//          max_matches: 1.., the most matches returned.
// Output   One PacsMatch per C-FIND response, in the PACS's order. Each field is "" (or
//          nullopt) when the PACS did not return it; PATIENT level fills only patient fields.
//          Values are as sent, trimmed of DICOM padding, converted to UTF-8 when the PACS
//          declares another Specific Character Set.
// Errors   INVALID_ARGUMENT naming the bad peer or query field (a study key at PATIENT level,
//          a malformed date range, ...). RESOURCE_EXHAUSTED when the PACS has more than
//          max_matches matches: the query is aborted and nothing returned, narrow it (a silent
//          truncation would hide patients). FAILED_PRECONDITION when modalities were asked
//          for and the PACS returns matches without Modalities in Study (0008,0061): it ignores
//          that key (DCMTK's dcmqrscp does), so its answer would be wrong. A final C-FIND
//          status other than success gives FAILED_PRECONDITION with the status in hex
//          (e.g. 0xA900 identifier does not match SOP class, 0xC000 unable to process).
//          Connection and association errors as in dicom/pacs_association.h.
// Cost     one association; O(matches) memory. Thread-safe.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::dicom {

enum class PacsLevel { kPatient, kStudy };
enum class PacsModel { kPatientRoot, kStudyRoot };

struct PacsQuery {
  PacsLevel level = PacsLevel::kStudy;
  PacsModel model = PacsModel::kPatientRoot;
  std::string patient_id;
  std::string patient_name;
  std::string study_date;  // a date or a range, see above
  std::string modalities;  // "CT\\PT": any of them
  std::string study_uid;
  std::string accession_number;
  std::size_t max_matches = 10000;
};

struct PacsMatch {
  std::string patient_id;
  std::string patient_name;
  std::string patient_sex;
  std::string patient_birth_date;  // YYYYMMDD
  std::string study_uid;
  std::string study_date;  // YYYYMMDD
  std::string study_description;
  std::string modalities;  // "CT\\PT" as the PACS lists them
  std::string accession_number;
  std::optional<int> number_of_instances;  // Number of Study Related Instances
};

Result<std::vector<PacsMatch>> pacs_find(const PacsPeer& peer, const PacsQuery& query);

}  // namespace soiq::dicom
