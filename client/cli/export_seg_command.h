#pragma once
// `soiq export-seg ID... -o OUT.dcm [--description TEXT] [--fractional [--oversample N]]`:
// imported structures as one binary DICOM Segmentation on the image series they were converted
// on, one segment per id in order (soiqd's ExportSeg); with --fractional a FRACTIONAL (OCCUPANCY)
// one of their coverage fractions, N x N lines per voxel (1-8, default 4). Prints one line: SOP
// instance, segments, frames, bytes, the referenced series.
// Exit 4 for an uploaded structure or structures of different series; nothing is left at OUT on
// failure.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_export_seg_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
