#include "client/cohort/synthetic_cohort.h"

#include <cmath>
#include <cstdio>

#include "core/geometry/primitives.h"

namespace soiq {

namespace {

// SplitMix64: tiny, and the same sequence everywhere (std:: distributions are not portable).
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * 0x1.0p-53; }
  int integer(int lo, int hi) { return lo + int(next() % uint64_t(hi - lo + 1)); }

 private:
  uint64_t state_;
};

// Semi-axes (x, y, z) in mm and the centre of the left structure (x > 0); the right one mirrors x.
struct Anatomy {
  const char* name;
  Vec3 semi_axes_mm;
  Vec3 left_centre_mm;
};

// LPS: +x left, +y posterior, +z superior. Sizes give ~3.5, ~1.5 and ~4 cm3.
constexpr Anatomy kAnatomy[] = {
    {"hippocampus", {6.0, 19.0, 7.5}, {28.0, 8.0, -16.0}},
    {"amygdala", {7.5, 7.0, 7.0}, {22.0, -14.0, -20.0}},
    {"caudate", {6.5, 14.0, 10.5}, {13.0, -6.0, 10.0}},
};

struct Placed {
  Vec3 centre_mm, semi_axes_mm;
};

// An ellipsoid with a gentle low-order bump: radial scale 1 + a*sin(2 theta)cos(phi) stays > 0,
// so the surface stays closed, star-shaped and outward.
TriangleMesh deformed_ellipsoid(const Placed& p, double bump) {
  TriangleMesh m = uv_sphere({0, 0, 0}, 1.0, 16, 32);
  for (Vec3& v : m.vertices_mm) {
    const double theta = std::acos(std::fmax(-1.0, std::fmin(1.0, v[2])));
    const double phi = std::atan2(v[1], v[0]);
    const double s = 1.0 + bump * std::sin(2 * theta) * std::cos(phi);
    for (int a = 0; a < 3; ++a) v[a] = p.centre_mm[a] + s * p.semi_axes_mm[a] * v[a];
  }
  return m;
}

int age_at(const std::string& birth, const std::string& study) {
  const int b = std::stoi(birth), s = std::stoi(study);
  return (s / 10000 - b / 10000) - ((s % 10000) < (b % 10000) ? 1 : 0);
}

std::string date(int year, int month, int day) {
  char text[16];
  std::snprintf(text, sizeof text, "%04d%02d%02d", year, month, day);
  return text;
}

Image synthetic_mr(const std::vector<Placed>& placed, const std::vector<double>& brightness, double phase) {
  Image image;
  ImageGeometry& g = image.geometry;
  g.dims = {64, 64, 48};
  g.spacing_mm = {2, 2, 2};
  g.origin_mm = {-63, -63, -47};  // centred on the origin
  image.voxels.resize(size_t(g.voxel_count()));
  size_t index = 0;
  for (int64_t k = 0; k < g.dims[2]; ++k) {
    for (int64_t j = 0; j < g.dims[1]; ++j) {
      for (int64_t i = 0; i < g.dims[0]; ++i) {
        const Vec3 p = g.index_to_physical({double(i), double(j), double(k)});
        double value = 100 + 15 * std::sin(p[0] / 23 + phase) * std::cos(p[1] / 31) + 0.1 * p[2];
        for (size_t s = 0; s < placed.size(); ++s) {
          // Normalised ellipsoidal distance: 1 on the surface. A smooth step that is ~1 inside
          // and falls to ~0 within a few mm outside.
          double d2 = 0;
          for (int a = 0; a < 3; ++a) {
            const double t = (p[a] - placed[s].centre_mm[a]) / placed[s].semi_axes_mm[a];
            d2 += t * t;
          }
          value += brightness[s] / (1 + std::exp((std::sqrt(d2) - 1.1) * 8));
        }
        image.voxels[index++] = float(value);
      }
    }
  }
  return image;
}

}  // namespace

std::vector<SyntheticPatient> synthetic_cohort(int patients, uint64_t seed) {
  std::vector<SyntheticPatient> cohort;
  Random random(seed);
  for (int n = 1; n <= patients; ++n) {
    SyntheticPatient p;
    char id[32];
    std::snprintf(id, sizeof id, "DEMO_%03d", n);
    p.patient_id = id;
    p.sex = random.next() % 2 ? "F" : "M";
    p.birth_date = date(random.integer(1940, 2000), random.integer(1, 12), random.integer(1, 28));
    p.study_date = date(random.integer(2015, 2025), random.integer(1, 12), random.integer(1, 28));
    p.study_uid = "2.25." + std::to_string(seed) + "." + std::to_string(n);
    p.series_uid = p.study_uid + ".1";
    p.study_description = "Synthetic brain MR";
    p.modality = "MR";
    const int age = age_at(p.birth_date, p.study_date);
    const double body = p.sex == "M" ? 1.03 : 0.97;  // structure sizes scale with head size
    std::vector<Placed> placed;
    std::vector<double> brightness;
    for (const Anatomy& a : kAnatomy) {
      const bool hippocampus = std::string(a.name) == "hippocampus";
      const double atrophy = hippocampus && age > 60 ? 1 - 0.004 * (age - 60) : 1.0;
      const double scale = std::cbrt(body * atrophy) * random.uniform(0.93, 1.07);
      for (const char* side : {"L", "R"}) {
        const double asymmetry = random.uniform(0.96, 1.04);
        Placed where;
        for (int axis = 0; axis < 3; ++axis) {
          where.semi_axes_mm[axis] = a.semi_axes_mm[axis] * scale * std::cbrt(asymmetry);
          where.centre_mm[axis] = a.left_centre_mm[axis] + random.uniform(-1.5, 1.5);
        }
        if (side[0] == 'R') where.centre_mm[0] = -where.centre_mm[0];
        p.structures.push_back({a.name, side, deformed_ellipsoid(where, random.uniform(0.0, 0.12))});
        placed.push_back(where);
        brightness.push_back(random.uniform(120, 170));
      }
    }
    p.image = synthetic_mr(placed, brightness, random.uniform(0, 6.28));
    cohort.push_back(std::move(p));
  }
  return cohort;
}

}  // namespace soiq
