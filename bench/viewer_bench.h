#pragma once
// `soiq-bench viewer [--runs R] [--soiqd PATH]`: what a web viewer (OHIF) asks when it opens a
// series, timed on soiqd (--http, SQLite, the original instances it keeps) and on Orthanc (Debian's,
// with its DICOMweb plugin), on the same study: STS_002's CT (48 slices of 161 x 143) and its
// RTSTRUCT sent to both by STOW-RS. The connections stay open over the runs, as a browser keeps them.
//   metadata  the series' /metadata, R runs, one client: p50 and p95 ms (48 items on both).
//   frames    each of the 48 /frames/1 once per run, one keep-alive client: p50 and p95 ms a frame;
//             and the 48 on 6 connections at once, as a browser fetches them: p50 ms for all 48.
//   series    the whole series retrieval (transfer-syntax=*): p50 ms.
// Checked, failing the run: /metadata holds the 48 instances on each server, each frame is native
// (Rows x Columns x 2 bytes), and both servers send the same frame bytes.
// Prints a markdown table. Orthanc missing (or its plugin) leaves one column saying why.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_viewer_bench(const CliArgs& args);

}  // namespace soiq::bench
