#pragma once
// Before a query computes anything: does any stored image answer to each image it names? A query
// naming an image no series has (a modality the store lacks, a mistyped uid) would otherwise drop
// every candidate in stage 2 and return an empty table as if nothing matched.
//
// Inputs   the store; the image references of the query's features and grid, each a series uid
//          or a modality code (already in DICOM's words: modality_names.h).
// Output   OK when each uid is a stored series and each modality is one some stored series has
//          (ASCII case-insensitive). Whether each candidate's own study has it is stage 2's
//          business, reported per structure.
// Errors   NOT_FOUND naming the reference and, for a modality, the modalities the store holds;
//          the store's errors.
// Cost     one lookup per uid. The modalities are read from the store (Store::counts) once and kept:
//          a modality seen before passes without a read, one not seen makes it read them again
//          before refusing, so an image uploaded since is never refused. (A modality whose last
//          series was deleted passes; its candidates are then reported skipped, per structure.)
// Thread-safety: one ImageRefsCheck serves concurrent queries.

#include <mutex>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"

namespace soiq::server {

class ImageRefsCheck {
 public:
  Status check(db::RecordStore& store, const std::vector<std::string>& refs);

 private:
  // Whether `modality` is among those last read; reads them again first when `fresh` is asked.
  Result<bool> known(db::RecordStore& store, const std::string& modality, bool fresh);

  std::mutex mutex_;
  std::vector<std::string> modalities_;  // as the store last listed them
};

}  // namespace soiq::server
