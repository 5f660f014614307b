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
// Cost     one skip-scan of the series' modalities (a seek per distinct modality) and one lookup
//          per uid.

#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"

namespace soiq::server {

Status check_image_refs(db::Store& store, const std::vector<std::string>& refs);

}  // namespace soiq::server
