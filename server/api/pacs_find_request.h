#pragma once
// PacsFind's request and answer in the API's words <-> dicom::pacs_find's (dicom/pacs_find.h),
// kept apart from the handler so the mapping is tested once.
//
// pacs_query_of: level and keys copied; max_matches 0 -> kDefaultPacsMatches, above
// kMaxPacsMatches INVALID_ARGUMENT. The keys themselves are checked by dicom::pacs_find.
// Study level uses the Study Root model (every study with its patient's attributes), patient
// level the Patient Root model.
// to_proto: number_of_instances -1 when the PACS did not return it.

#include "core/base/status.h"
#include "dicom/pacs_find.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

inline constexpr int kDefaultPacsMatches = 1000;
inline constexpr int kMaxPacsMatches = 10000;

Result<dicom::PacsQuery> pacs_query_of(const v1::PacsFindRequest& request);
v1::PacsMatch to_proto(const dicom::PacsMatch& match);

}  // namespace soiq::server
