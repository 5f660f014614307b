#pragma once
// `soiq-bench dicomweb [--patients N] [--batch B] [--runs R] [--soiqd PATH]`: DICOMweb side by side,
// soiqd (--http, SQLite) and Orthanc (Debian's, with its DICOMweb plugin), on the same data.
//   data     N synthetic patients, each one study of one 16 x 16 CT slice (written with DCMTK from
//            tests/data/dicom/CT_small.dcm's header): PatientID DW000001…, a name, a sex, a study
//            date spread over 2000-2019 — the DICOM world's metadata with as few pixels as can be,
//            so what is measured is the index, not image decoding.
//   STOW-RS  the N instances POSTed in requests of B instances, one client, to each server: instances/s.
//   QIDO-RS  R runs of each study query (first page, PatientID prefix, a month of StudyDate,
//            PatientName wildcard, one StudyInstanceUID, a deep page by offset), one client, each
//            server: p50 and p95 latency in ms and the rows answered (which must agree).
// Prints two markdown tables. Orthanc missing (or its plugin) leaves its columns out, saying why.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_dicomweb_bench(const CliArgs& args);

}  // namespace soiq::bench
