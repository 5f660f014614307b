#include "client/cohort/bilateral_structures.h"

#include <cmath>

namespace soiq::cohort {
namespace {

constexpr Anatomy kAnatomy[] = {
    {"hippocampus", {6.0, 19.0, 7.5}, {28.0, 8.0, -16.0}}, {"amygdala", {7.5, 7.0, 7.0}, {22.0, -14.0, -20.0}},
    {"caudate", {6.5, 14.0, 10.5}, {13.0, -6.0, 10.0}},    {"putamen", {7.0, 15.0, 10.0}, {25.0, -2.0, 2.0}},
    {"thalamus", {9.0, 15.0, 10.0}, {11.0, 16.0, 4.0}},
};

}  // namespace

std::span<const Anatomy> deep_brain_anatomy() { return kAnatomy; }

std::vector<PlacedStructure> place_bilateral_structures(const StructureStyle& style, const std::string& sex,
                                                        int age_years, SplitMix64& random) {
  std::vector<PlacedStructure> out;
  const double body = sex == "M" ? 1.03 : 0.97;  // structure sizes scale with head size
  for (const Anatomy& a : deep_brain_anatomy().first(size_t(style.kinds))) {
    const bool atrophies = std::string(a.name) == "hippocampus" && age_years > 60;
    const double atrophy = atrophies ? 1 - style.hippocampus_atrophy_per_year * (age_years - 60) : 1.0;
    const double scale = std::cbrt(body * atrophy) * random.uniform(0.92, 1.08);
    for (const char* side : {"L", "R"}) {
      const double asymmetry = std::cbrt(random.uniform(0.95, 1.05));
      PlacedStructure s;
      s.name = a.name;
      s.laterality = side;
      for (int axis = 0; axis < 3; ++axis) {
        s.ellipsoid.semi_axes_mm[axis] = a.semi_axes_mm[axis] * scale * asymmetry;
        s.ellipsoid.centre_mm[axis] = a.left_centre_mm[axis] + random.uniform(-1.5, 1.5);
      }
      if (side[0] == 'R') s.ellipsoid.centre_mm[0] = -s.ellipsoid.centre_mm[0];
      s.brightness = random.uniform(style.blob_brightness_min, style.blob_brightness_max);
      out.push_back(std::move(s));
    }
  }
  // Shapes after places: the image needs only the places, and their draws do not depend on these.
  for (PlacedStructure& s : out) {
    s.bump = draw_radial_bump(random);
    s.triangles = random.integer(style.min_triangles, style.max_triangles);
  }
  return out;
}

TriangleMesh structure_surface(const PlacedStructure& s) {
  return deformed_ellipsoid(s.ellipsoid, s.bump, s.triangles);
}

}  // namespace soiq::cohort
