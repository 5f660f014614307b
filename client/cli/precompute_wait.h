#pragma once
// `--wait` of the upload and import commands: returns once soiqd has precomputed every structure
// queued (this command's among them), so that a script's next query reads stored values and its
// stage 1 can filter on them. Polls `soiq info`'s queue length every 200 ms, with a progress bar on
// a terminal. Returns false at once when soiqd runs with --precompute off (nothing to wait for).
// Errors: the client's (UNAVAILABLE, ...); CANCELLED when the user interrupts (the upload stays).

#include "client/soiq_client.h"
#include "core/base/status.h"

namespace soiq::cli {

Result<bool> wait_for_precompute(const client::Client& c);

// wait_for_precompute for --wait: a note on stderr (unless --quiet) when there was nothing to wait for.
Status wait_option(const client::Client& c);

}  // namespace soiq::cli
