#pragma once
// Why stage 2 dropped structures, counted by reason, so that a partial answer says how many and
// why ("1000 skipped: NOT_FOUND: no image series 'PT' in their study ...") instead of a table that
// looks as if nothing matched.
//
// add(error, study_uid, id)   one dropped structure. Its reason is the error's code and message,
//                             with "study <its own study uid>" written "their study" and
//                             "structure <its id>:" written "the structure:", so that structures
//                             dropped for the same cause share one reason.
// groups()                    every reason with its count and its first kExampleIds structure ids,
//                             largest count first (ties in order of first appearance).
// Cost O(log reasons) per add. Not thread-safe: one query's thread adds.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "server/app/query.h"

namespace soiq::server {

class QuerySkips {
 public:
  static constexpr size_t kExampleIds = 5;

  void add(const Status& error, const std::string& study_uid, int64_t structure_id);
  std::vector<QuerySkip> groups() const;

 private:
  std::vector<QuerySkip> groups_;        // in order of first appearance
  std::map<std::string, size_t> index_;  // reason -> groups_
};

}  // namespace soiq::server
