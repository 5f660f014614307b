#pragma once
// soiq-bench codec [--runs N] [--label LABEL_IMAGE] [--image IMAGE] [--decode-only]: candidate
// encodings of a stored surface (db/surface_blob.h) side by side: bytes, encode and decode time,
// lossless check, on a 100k- and a 400k-triangle sphere, a query-bench structure and, with --label,
// the marching-cubes surface of a label image in float64 and float32 coordinates; then, for each
// mesh, the version 3 decode against a memcpy of the bytes it decodes to (median and minimum of the
// runs, the two called in turn); then the image blob's codecs. Markdown tables on stdout.
// --decode-only prints the decode-against-memcpy table alone.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_surface_codec_bench(const CliArgs& args);

}  // namespace soiq::bench
