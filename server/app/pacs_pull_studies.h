#pragma once
// PacsPull's transfer: the studies asked for (or every study of a patient, found by C-FIND) pulled
// by C-GET into one folder, ready for import_dicom_folder (server/app/dicom_import.h). The import only
// starts when every study came complete, so a pull that fails midway stores nothing.
//
// Inputs   peer: the configured PACS. request: study_uids (distinct, at most kMaxPulledStudies),
//          or, when it has none, patient_id (an exact id, no wildcards: every study of that
//          patient). dir: an empty folder; study n (from 1) goes to dir/n/. max_bytes: the most
//          bytes of instances accepted in all (soiqd --max-upload-bytes). progress: after each
//          instance; false cancels.
// Output   The received files, relative to dir, and their total size.
// Errors   INVALID_ARGUMENT: neither or both of study_uids and patient_id, repeated or too many
//          studies, a wildcard in patient_id. NOT_FOUND: the patient has no study on the PACS, or
//          a study has no instances. RESOURCE_EXHAUSTED: over max_bytes, or the patient has more
//          than kMaxPulledStudies studies (pull them by uid). CANCELLED when progress returned
//          false. Otherwise dicom::pacs_find's and dicom::pacs_pull's errors unchanged.
// Cost     one C-FIND when by patient, then one C-GET association per study.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::server {

inline constexpr int kMaxPulledStudies = 100;

// What to pull: study uids, or, when there are none, every study of one patient.
struct PullRequest {
  std::vector<std::string> study_uids;
  std::string patient_id;
};

// After each instance received: study n of studies (from 1), instances received so far in all,
// instances the PACS says remain in this study.
struct PullProgress {
  int study = 0, studies = 0;
  int received = 0, remaining = 0;
};

struct PulledFiles {
  std::vector<std::string> paths;  // relative to dir
  int64_t bytes = 0;
  int studies = 0;
};

Result<PulledFiles> pacs_pull_studies(const dicom::PacsPeer& peer, const PullRequest& request, const std::string& dir,
                                      int64_t max_bytes, const std::function<bool(const PullProgress&)>& progress);

}  // namespace soiq::server
