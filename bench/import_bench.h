#pragma once
// `soiq-bench import DIR... [--runs N] [--soiqd PATH]`: DICOM import throughput, one
// case per DIR (a patient's files, e.g. ../shared/data/sts/dicom/STS_002), best of N runs each:
//   dcmdump      DCMTK's own dcmdump reading every file of the case, one process, output to
//                /dev/null: the floor (parsing every element, nothing converted)
//   import       dicom::import_dicom in-process: scan, image series with geometry and rescale,
//                every RT Structure Set ROI filled on its series' grid and meshed (what soiqd does
//                before it writes)
//   soiq import  the whole path through a real soiqd (child process, own SQLite file): the client
//                reads and streams the files, soiqd imports and stores them in one transaction
//                (runs after the first re-import the same files, updating in place)
// Then one row per RT Structure Set ROI: its contours, grid, voxels, the even-odd contour fill
// (core/voxelize/fill_contours, the 1D line filler) alone and with the marching-cubes surface
// (dicom::convert_rt_struct), best of N. Prints two markdown tables.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_import_bench(const CliArgs& args);

}  // namespace soiq::bench
