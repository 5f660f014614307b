#include "dicom/referenced_series.h"

#include <map>
#include <unordered_set>

namespace soiq::dicom {

Result<std::string> referenced_series(const RtStructureSet& rs, const DicomScan& scan) {
  for (const auto& uid : rs.referenced_series_uids)
    if (scan.find_series(uid) != nullptr) return uid;

  const std::unordered_set<std::string> images(rs.referenced_image_uids.begin(), rs.referenced_image_uids.end());
  std::string best;
  size_t best_hits = 0;
  for (const auto& series : scan.series) {
    size_t hits = 0;
    for (const auto& inst : series.instances) hits += images.count(inst.sop_instance_uid);
    if (hits > best_hits) best = series.series_uid, best_hits = hits;
  }
  if (best_hits > 0) return best;

  const std::string who = "RT Structure Set '" + rs.path + "'";
  const std::string todo = "; import the referenced image series together with the structure set";
  if (!rs.referenced_series_uids.empty()) {
    std::string uids;
    for (const auto& u : rs.referenced_series_uids) uids += (uids.empty() ? "" : ", ") + u;
    return not_found(who + " references image series " + uids + ", which is not among the imported files" + todo);
  }
  if (!rs.referenced_image_uids.empty())
    return not_found(who + " references " + std::to_string(rs.referenced_image_uids.size()) + " image(s) (first " +
                     rs.referenced_image_uids.front() + ") none of which is among the imported files" + todo);
  // Nothing referenced: the frame of reference is the last clue, used only when unambiguous.
  std::string match;
  int matches = 0;
  for (const auto& series : scan.series) {
    if (series.modality == "RTSTRUCT" || series.frame_of_reference_uid.empty()) continue;
    for (const auto& f : rs.frame_of_reference_uids)
      if (f == series.frame_of_reference_uid) match = series.series_uid, ++matches;
  }
  if (matches == 1) return match;
  return not_found(who + " references no image series, and " + std::to_string(matches) +
                   " imported series share its frame of reference" + todo);
}

}  // namespace soiq::dicom
