#include "server/app/query_skips.h"

#include <algorithm>

namespace soiq::server {

void QuerySkips::add(const Status& error, const std::string& study_uid, int64_t structure_id) {
  std::string reason = std::string(status_code_name(error.code())) + ": " + error.message();
  const std::string own = "study " + study_uid;
  if (!study_uid.empty()) {
    for (size_t at = reason.find(own); at != std::string::npos; at = reason.find(own, at + 1))
      reason.replace(at, own.size(), "their study");
  }
  // Errors that name the structure itself ("structure 12: none of the region's ...") share a reason
  // with those of other structures once it is "the structure".
  const std::string self = "structure " + std::to_string(structure_id) + ":";
  if (const size_t at = reason.find(self); at != std::string::npos) reason.replace(at, self.size(), "the structure:");
  auto [it, fresh] = index_.emplace(reason, groups_.size());
  if (fresh) groups_.push_back(QuerySkip{std::move(reason), 0, {}});
  QuerySkip& g = groups_[it->second];
  ++g.count;
  if (g.structure_ids.size() < kExampleIds) g.structure_ids.push_back(structure_id);
}

std::vector<QuerySkip> QuerySkips::groups() const {
  std::vector<QuerySkip> out = groups_;
  std::stable_sort(out.begin(), out.end(), [](const QuerySkip& a, const QuerySkip& b) { return a.count > b.count; });
  return out;
}

}  // namespace soiq::server
