#pragma once
// soiq-bench codec [--runs N] [--label LABEL_IMAGE]: candidate encodings of a stored surface
// (db/surface_blob.h) side by side: bytes, encode and decode time, lossless check, on a 100k-triangle
// sphere, a query-bench structure and, with --label, the marching-cubes surface of a label image in
// float64 and float32 coordinates. A Markdown table on stdout.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_surface_codec_bench(const CliArgs& args);

}  // namespace soiq::bench
