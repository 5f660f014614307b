#pragma once
// `soiq convert ID -o OUT.{nii.gz,nii,nrrd,mha} [--spacing S|SX,SY,SZ [--margin N] | --series UID
//  | --series-modality M] [--even-odd]`: the volume model of stored structure ID, converted by
// soiqd. soiqd sends NIfTI (gzip); other extensions are re-encoded here with the same geometry.
// Prints the summary line of the offline command: voxels, volume, grid, defects, ms -> OUT.
// The offline `soiq convert MESH ...` is convert_command.h; main.cpp picks by the operand.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_remote_convert_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
