#pragma once
// `soiq convert MESH -o OUT [--reference IMAGE | --spacing S|SX,SY,SZ [--margin N]] [--robust]
//  [--even-odd] [--threads N] [--ras]`: a surface model -> its mask (0/1 uint8), offline.

namespace soiq::cli {

int run_convert_command(int argc, char** argv);

}  // namespace soiq::cli
