#pragma once
// `soiq download ID -o OUT.{stl,obj,ply,vtk,vtp} [--ras]`: the stored surface model of structure
// ID from soiqd, in the output's format (LPS mm; --ras converts to RAS). Prints "N bytes -> OUT".

#include "client/soiq_client.h"

namespace soiq::cli {

int run_download_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
