#pragma once
// `soiq export-rtstruct ID... -o OUT.dcm [--description TEXT]`: imported structures as one DICOM
// RT Structure Set on the image series they were imported on, one ROI per id in order (soiqd's
// ExportRtStruct): each stored surface cut into CLOSED_PLANAR contours on every slice plane of
// that series. Prints one line: SOP instance, ROIs, contours, points, bytes, the referenced series.
// Exit 2 for structures of different series, 3 for an unknown id, 4 for an uploaded structure;
// nothing is left at OUT on failure.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_export_rt_struct_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
