#pragma once
// `soiq query [stage-1 filters] [--where 'FEATURE OP N']... [--select FEATURE]...
//  [--order-by FEATURE [--desc]] [--limit N] [--spacing S | --series-modality M]
//  [--format table|json|csv]`: the two-stage query on soiqd (options in query_args.h).
// stdout: one row per matching structure — id, patient_id, study_uid, name, laterality, then one
// column per feature (named as written canonically, e.g. "mean[shell:5,PT]"); csv and json rows
// print as they arrive, a table when all are in.
// stderr: a progress bar (only on a terminal) and one summary line: candidates, computed, cache
// hits, matched, returned, failed, stage times; then the first failures, one per line.
// Ctrl-C cancels the query on the server (exit 6, "query cancelled by the client").

#include "client/soiq_client.h"

namespace soiq::cli {

int run_query_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
