#include "server/app/pacs_pull_studies.h"

#include <filesystem>
#include <set>
#include <system_error>

#include "dicom/pacs_find.h"
#include "dicom/pacs_pull.h"

namespace soiq::server {
namespace {

Result<std::vector<std::string>> studies_to_pull(const dicom::PacsPeer& peer, const PullRequest& r) {
  if (r.study_uids.empty() == r.patient_id.empty())
    return invalid_argument("give either study uids or a patient id to pull (not both, not neither)");
  if (!r.study_uids.empty()) {
    if (r.study_uids.size() > size_t(kMaxPulledStudies))
      return invalid_argument(std::to_string(r.study_uids.size()) + " studies asked; one pull takes at most " +
                              std::to_string(kMaxPulledStudies));
    std::set<std::string> seen;
    for (const std::string& uid : r.study_uids)
      if (!seen.insert(uid).second) return invalid_argument("study " + uid + " is named twice");
    return r.study_uids;
  }
  if (r.patient_id.find_first_of("*?") != std::string::npos)
    return invalid_argument("patient id '" + r.patient_id +
                            "' has a wildcard; a pull takes one exact patient id (list them with 'soiq pacs find')");
  dicom::PacsQuery q;
  q.level = dicom::PacsLevel::kStudy;
  q.model = dicom::PacsModel::kStudyRoot;
  q.patient_id = r.patient_id;
  q.max_matches = kMaxPulledStudies;
  Result<std::vector<dicom::PacsMatch>> found = dicom::pacs_find(peer, q);
  if (!found.ok() && found.status().code() == StatusCode::kResourceExhausted)
    return resource_exhausted("patient '" + r.patient_id + "' has more than " + std::to_string(kMaxPulledStudies) +
                              " studies on " + dicom::describe_pacs_peer(peer) + "; pull them by study uid");
  SOIQ_RETURN_IF_ERROR(found.status());
  std::vector<std::string> uids;
  std::set<std::string> seen;
  for (const dicom::PacsMatch& m : *found)
    if (!m.study_uid.empty() && seen.insert(m.study_uid).second) uids.push_back(m.study_uid);
  if (uids.empty())
    return not_found("patient '" + r.patient_id + "' has no study on " + dicom::describe_pacs_peer(peer));
  return uids;
}

}  // namespace

Result<PulledFiles> pacs_pull_studies(const dicom::PacsPeer& peer, const PullRequest& request, const std::string& dir,
                                      int64_t max_bytes, const std::function<bool(const PullProgress&)>& progress) {
  SOIQ_ASSIGN_OR_RETURN(const std::vector<std::string> uids, studies_to_pull(peer, request));
  PulledFiles out;
  out.studies = int(uids.size());
  bool over_limit = false;
  for (size_t n = 0; n < uids.size(); ++n) {
    const std::string sub = std::to_string(n + 1);
    const int received_before = int(out.paths.size());
    auto on_instance = [&](const dicom::PacsPullProgress& p) {
      std::error_code ec;
      const auto size = std::filesystem::file_size(p.path, ec);
      out.bytes += ec ? 0 : int64_t(size);
      if (out.bytes > max_bytes) {
        over_limit = true;
        return false;
      }
      const PullProgress e{int(n + 1), int(uids.size()), received_before + p.received, p.remaining};
      return !progress || progress(e);
    };
    Result<dicom::PacsPullResult> pulled = dicom::pacs_pull(peer, uids[n], dir + "/" + sub, on_instance);
    if (over_limit)
      return resource_exhausted("the pull is larger than the server's limit of " + std::to_string(max_bytes) +
                                " bytes (soiqd --max-upload-bytes); nothing was imported");
    SOIQ_RETURN_IF_ERROR(pulled.status());
    for (const std::string& path : pulled->paths)
      out.paths.push_back(std::filesystem::path(path).lexically_relative(dir).generic_string());
  }
  return out;
}

}  // namespace soiq::server
