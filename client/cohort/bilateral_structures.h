#pragma once
// Where a synthetic patient's deep-brain structures lie: each kind on both sides, as a deformed
// ellipsoid of plausible size and place (deformed_ellipsoid.h), with its brightness in the image.
//
// deep_brain_anatomy(): the five kinds, in this order: hippocampus (~3.5 cm3), amygdala (~1.5 cm3),
//   caudate (~4 cm3), putamen (~4.4 cm3), thalamus (~5.7 cm3), with semi-axes (x, y, z) and the
//   centre of the left one (LPS mm: +x the patient's left, +y posterior, +z superior).
// place_bilateral_structures(style, sex, age, random): for the first `style.kinds` kinds, L then R
//   (R mirrors the centre's x). Draws, in order, per kind: a size factor in [0.92, 1.08) (times
//   1.03 for sex "M", 0.97 otherwise, in volume; and for the hippocampus after 60 the volume loses
//   style.hippocampus_atrophy_per_year a year); per side: an asymmetry in [0.95, 1.05) of the
//   volume, a jitter of the centre in [-1.5, 1.5) mm per axis, the brightness in
//   [blob_brightness_min, blob_brightness_max). Then per structure, in output order: its radial
//   bump (draw_radial_bump) and its triangle count in [min_triangles, max_triangles].
// structure_surface(s): its closed, outward mesh (deformed_ellipsoid).
// Inputs: 1 <= kinds <= 5, 8 <= min_triangles <= max_triangles <= 2^31 - 1, brightness min <= max.
// Cost: O(kinds) to place; O(triangles) per surface. Thread-safe given one generator per thread.

#include <span>
#include <string>
#include <vector>

#include "client/cohort/deformed_ellipsoid.h"
#include "client/cohort/split_mix_64.h"

namespace soiq::cohort {

struct Anatomy {
  const char* name;
  Vec3 semi_axes_mm;
  Vec3 left_centre_mm;
};

std::span<const Anatomy> deep_brain_anatomy();

struct StructureStyle {
  int kinds = 3;  // the first `kinds` of deep_brain_anatomy()
  int min_triangles = 1024, max_triangles = 1024;
  double blob_brightness_min = 120, blob_brightness_max = 170;  // added to the image over each
  double hippocampus_atrophy_per_year = 0;                      // of its volume, after 60
};

struct PlacedStructure {
  std::string name;        // "hippocampus", ...
  std::string laterality;  // "L" or "R"
  Ellipsoid ellipsoid;
  RadialBump bump;
  int triangles = 0;
  double brightness = 0;
};

std::vector<PlacedStructure> place_bilateral_structures(const StructureStyle& style, const std::string& sex,
                                                        int age_years, SplitMix64& random);

TriangleMesh structure_surface(const PlacedStructure& s);

}  // namespace soiq::cohort
