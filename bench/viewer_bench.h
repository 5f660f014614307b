#pragma once
// `soiq-bench viewer [--runs R] [--soiqd PATH]`: what a web viewer (OHIF) asks when it opens a
// series, timed on soiqd (--http, SQLite, the original instances it keeps) and on Orthanc (Debian's,
// with its DICOMweb plugin), on the same study: STS_002's CT (48 slices of 161 x 143) sent to both
// by STOW-RS.
//   metadata  the series' /metadata, R runs, one client: p50 and p95 ms (48 items on both).
//   frames    each of the 48 /frames/1 once per run, one keep-alive client: p50 and p95 ms a frame;
//             and the 48 on 6 connections at once, as a browser fetches them: p50 ms for all 48.
//   series    the whole series retrieval (transfer-syntax=*): p50 ms.
// The frames both servers send must be the same bytes (checked; a difference fails the run).
// Prints a markdown table. Orthanc missing (or its plugin) leaves its columns out, saying why.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_viewer_bench(const CliArgs& args);

}  // namespace soiq::bench
