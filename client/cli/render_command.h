#pragma once
// `soiq render ID [--image MODALITY|SERIES_UID|none] [--plane axial|coronal|sagittal]
//  [--slice K | --through largest|centroid] [--window C,W] [--montage] [--width PX]
//  [--patient-caption] [--quality Q] -o FILE.png|.svg|.jpg`: a picture of a stored structure over a
// slice of its image, drawn by soiqd (the Render RPC; server/app/structure_render.h says what is
// drawn). The format follows FILE's extension. Prints one line: plane, slice, image, window, size.
// Nothing is left at FILE on failure.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_render_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
