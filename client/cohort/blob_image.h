#pragma once
// A synthetic MR-like image over a patient's structures: a smooth background plus a soft bright
// blob over each structure, so mean intensities inside, in a shell and in a core differ, and differ
// between structures.
//
// Inputs: the style (dims >= 1 per axis; background level and ripple amplitude in image units), the
//   structures (bilateral_structures.h) and a phase in radians (image_phase(seed) draws one).
// Output: a float32 image of `dims` voxels of 2 mm, identity direction, centred on the origin (LPS),
//   whose value at a voxel centre x (mm) is
//     background + ripple * sin(x / 19 + phase) * cos(y / 27) + 0.3 z
//     + sum over structures of brightness / (1 + exp(7 (d - 1.15))),
//   d the normalised ellipsoidal distance to the structure's ellipsoid (1 on it; the radial bump is
//   ignored): about `brightness` inside, falling to ~0 within a few mm outside.
// image_phase(seed): a phase in [0, 6.28) from its own stream, so it does not depend on how many
//   structures a patient has.
// Cost: O(voxels x structures). Thread-safe.

#include <array>
#include <cstdint>
#include <vector>

#include "client/cohort/bilateral_structures.h"
#include "core/base/image.h"

namespace soiq::cohort {

struct ImageStyle {
  std::array<int64_t, 3> dims = {64, 64, 48};
  double background = 100;
  double ripple = 15;
};

Image blob_image(const ImageStyle& style, const std::vector<PlacedStructure>& structures, double phase);

double image_phase(uint64_t seed);

}  // namespace soiq::cohort
