#pragma once
// `soiq-bench pacs DICOM_DIR --patient ID [--runs N] [--soiqd PATH]`: one patient's DICOM files
// (e.g. ../shared/data/sts/STS_002) loaded into a real PACS with DCMTK's storescu, then pulled into
// a fresh soiqd (`soiq pacs pull`: C-FIND, C-GET of every instance, the import, the store) and one
// of its structures pushed back as a DICOM SEG (`soiq pacs push`: the SEG written, C-STORE), best
// and median of N runs, against each PACS: DCMTK's dcmqrscp and Orthanc (Debian's `orthanc`, when
// installed). Each pull is timed with Nagle's algorithm off on soiq's association (soiqd's
// default, TCP_NODELAY) and on (TCP_NODELAY=0 in soiqd's environment), which is what made pulls
// from Orthanc 10x slower. Prints a markdown table.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_pacs_bench(const CliArgs& args);

}  // namespace soiq::bench
