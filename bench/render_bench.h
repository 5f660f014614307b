#pragma once
// `soiq-bench render [--runs R] [--patients N] [--soiqd PATH]`: what pictures cost through soiqd
// (--http, SQLite, 2 workers).
//   slice      a synthetic 512 x 512 x 64 CT (0.7 x 0.7 x 2.5 mm: air, a body of soft tissue with
//              noise, a bone ring) with a 30 mm sphere uploaded in its study. R renders of its
//              largest slice by the Render RPC (PNG, 512 px wide; the first, which decodes the image
//              and converts the structure, reported apart): p50 and p95; beside them the time to
//              read that slice from the store, in this process on the same file (the image blob
//              read and decoded: soiq stores an image whole, so reading a slice is reading it).
//   thumbnails `soiq demo-load --patients N` (6 structures each; N = 17 gives 102), then the first
//              100 structures' /soiq/v1/structures/{id}/thumbnail over HTTP, 6 at a time as a
//              browser fetches them: the whole page's time, cold (nothing converted on the
//              images' grids yet) and warm (again).
// Prints one markdown table.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_render_bench(const CliArgs& args);

}  // namespace soiq::bench
