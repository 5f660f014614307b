#pragma once
// A QueryRequest checked and turned into the application's Query (server/app/query.h): the stage-1
// filter for the store, the features read (predicates', then select's, then order_by's), and one
// FeatureAsk that covers them all (regions x images, so every value is in one computation); and
// the engine's rows, progress and summary turned back into QueryEvents.
//
// parse_query errors: INVALID_ARGUMENT naming the field — bad sex, laterality or date; min age >
// max age; unknown feature; a bad region; an intensity feature without an image or a shape feature
// with one; a predicate or order on an array feature (centroid_mm, bbox_mm); an unset or unknown
// comparison; limit < 0. A limit of 0, or above `result_cap`, is `result_cap`.

#include "core/base/status.h"
#include "server/app/query.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

Result<Query> parse_query(const v1::QueryRequest& request, int result_cap);

v1::QueryEvent to_event(const QueryProgress& p);
v1::QueryEvent to_event(const QueryRow& r);
v1::QueryEvent to_event(const QuerySummary& s);

}  // namespace soiq::server
