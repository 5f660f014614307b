#pragma once
// `soiq compare A B [--label-a N] [--label-b N]`: overlap of two masks on the same grid (the paper's
// IoU, Dice, voxels only in A / only in B). Exits 0 when compared, 2 on different grids.

namespace soiq::cli {

int run_compare_command(int argc, char** argv);

}  // namespace soiq::cli
