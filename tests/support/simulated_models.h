#pragma once
// The paper's simulated models SM1-SM11 (docs/DESIGN.md, its Table 3): a thick spherical shell of inner
// radius R1 and outer radius R2 centred at the origin, plus w flat ring "stripes" 4 mm thick whose
// outer radius is R3, spread evenly over z in (-R2/2, R2/2): stripe s has its mid-plane at
// z_s = -R2/2 + (s + 1/2) R2 / w.
//
// A point p (LPS mm) is inside iff |p| >= R1 and (|p| <= R2 or, for some stripe s,
// sqrt(x^2 + y^2) <= R3_s and |z - z_s| <= 2): the rings are attached to the shell and never
// cross its hollow.
//
// Our choice of the 11 (R1/R2, w, R3) combinations (the paper gives the ranges, not the table):
//   SM1 30/50 w0 | SM2 45/50 w0 | SM3 30/50 w1 55 | SM4 45/50 w1 60 | SM5 30/50 w2 75 |
//   SM6 45/50 w3 55 | SM7 30/50 w4 60 | SM8 45/50 w5 75 | SM9 30/50 w6 random |
//   SM10 45/50 w7 random | SM11 30/50 w7 75
// "random": R3 per stripe = 55 + 20 * (g() / 2^32), g a std::mt19937 seeded with 1, drawn in
// model order (SM9's 6 stripes, then SM10's 7), so the set is the same on every platform.
//
// V1: the analytic voxel-centre test on an axis-aligned grid of spacing S centred on the origin
// (voxel centre at 0), covering the object plus a margin of 3 voxels. S1: marching cubes of V1.

#include <string>
#include <vector>

#include "core/base/image.h"

namespace soiq::bench {

struct SimModel {
  std::string name;  // "SM1" .. "SM11"
  double r1_mm = 0, r2_mm = 0;
  std::vector<double> stripe_r3_mm;  // one outer radius per stripe; size() = w
};

std::vector<SimModel> simulated_models();

// V1 of `model` at `spacing_mm` (see above).
Mask simulated_volume(const SimModel& model, double spacing_mm);

}  // namespace soiq::bench
