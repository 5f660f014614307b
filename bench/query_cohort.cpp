#include "bench/query_cohort.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/geometry/primitives.h"
#include "db/age_years.h"

namespace soiq::bench {
namespace {

// SplitMix64: the same sequence on every machine (std:: distributions are not portable).
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
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

std::string date(int year, int month, int day) {
  char text[16];
  std::snprintf(text, sizeof text, "%04d%02d%02d", year, month, day);
  return text;
}

double age_at(const std::string& birth, const std::string& study) {
  const Result<std::optional<double>> a = db::age_years(birth, study);
  return a.ok() && a->has_value() ? **a : -1;
}

// Passes the filter, with a year of margin on the age so rounding can never decide.
bool near_filter(const CohortPatient& p) {
  const double age = age_at(p.patient.birth_date, p.study.study_date);
  return p.patient.sex == "F" && p.study.modality == "MR" && p.study.study_date >= "20200101" &&
         p.study.study_date <= "20231231" && age >= 59 && age <= 76;
}

void draw_background(CohortPatient& p, Rng& rng) {
  p.patient.sex = rng.next() % 2 ? "F" : "M";
  const int birth_year = rng.integer(1930, 2005);
  p.patient.birth_date = date(birth_year, rng.integer(1, 12), rng.integer(1, 28));
  p.study.study_date = date(rng.integer(std::max(2010, birth_year + 1), 2025), rng.integer(1, 12), rng.integer(1, 28));
  const int m = rng.integer(0, 99);
  p.study.modality = m < 50 ? "MR" : m < 85 ? "CT" : "PT";
  p.study.description = p.study.modality == "MR" ? "Brain MR" : p.study.modality == "CT" ? "Head CT" : "Brain PET";
}

void draw_matched(CohortPatient& p, Rng& rng) {
  p.patient.sex = "F";
  const int study_year = rng.integer(2020, 2023);
  p.study.study_date = date(study_year, rng.integer(1, 12), rng.integer(1, 28));
  // Born 61-74 years before, on a day that keeps the age within [61, 75).
  p.patient.birth_date = date(study_year - rng.integer(62, 74), rng.integer(1, 12), rng.integer(1, 28));
  p.study.modality = "MR";
  p.study.description = "Brain MR";
}

struct Anatomy {
  const char* name;
  Vec3 semi_axes_mm;
  Vec3 left_centre_mm;  // LPS: +x left, +y posterior, +z superior
};

constexpr Anatomy kAnatomy[] = {
    {"hippocampus", {6.0, 19.0, 7.5}, {28.0, 8.0, -16.0}}, {"amygdala", {7.5, 7.0, 7.0}, {22.0, -14.0, -20.0}},
    {"caudate", {6.5, 14.0, 10.5}, {13.0, -6.0, 10.0}},    {"putamen", {7.0, 15.0, 10.0}, {25.0, -2.0, 2.0}},
    {"thalamus", {9.0, 15.0, 10.0}, {11.0, 16.0, 4.0}},
};

struct Placed {
  Vec3 centre_mm, semi_axes_mm;
  double brightness = 0;
};

// Low-frequency radial perturbation: a few products of sines and cosines of order <= 3 whose
// amplitudes sum to < 0.25, so the radius stays positive and smooth.
struct Perturbation {
  double amplitude[4], phase[4];
  int order[4];
  double at(double theta, double phi) const {
    double s = 1;
    for (int i = 0; i < 4; ++i)
      s += amplitude[i] * std::sin(order[i] * theta + phase[i]) * std::cos((i + 1) * phi + phase[i]);
    return s;
  }
};

TriangleMesh deformed_ellipsoid(const Placed& p, int triangles, const Perturbation& bump) {
  TriangleMesh m = uv_sphere_with_triangles({0, 0, 0}, 1.0, triangles);
  for (Vec3& v : m.vertices_mm) {
    const double theta = std::acos(std::fmax(-1.0, std::fmin(1.0, v[2])));
    const double phi = std::atan2(v[1], v[0]);
    const double s = bump.at(theta, phi);
    for (int a = 0; a < 3; ++a) v[a] = p.centre_mm[a] + s * p.semi_axes_mm[a] * v[a];
  }
  return m;
}

std::vector<Placed> placements(const CohortPatient& p, Rng& rng) {
  std::vector<Placed> out;
  const double body = p.patient.sex == "M" ? 1.03 : 0.97;
  for (const Anatomy& a : kAnatomy) {
    const double scale = std::cbrt(body) * rng.uniform(0.92, 1.08);
    for (int side = 0; side < 2; ++side) {
      const double asymmetry = std::cbrt(rng.uniform(0.95, 1.05));
      Placed where;
      for (int axis = 0; axis < 3; ++axis) {
        where.semi_axes_mm[axis] = a.semi_axes_mm[axis] * scale * asymmetry;
        where.centre_mm[axis] = a.left_centre_mm[axis] + rng.uniform(-1.5, 1.5);
      }
      if (side == 1) where.centre_mm[0] = -where.centre_mm[0];
      where.brightness = rng.uniform(40, 160);
      out.push_back(where);
    }
  }
  return out;
}

}  // namespace

std::vector<CohortPatient> query_cohort_patients(const QueryCohortSize& size, uint64_t seed) {
  std::vector<CohortPatient> out(size_t(size.patients));
  Rng rng(seed);
  const int matched = std::min(size.matched, size.patients);
  for (int n = 0; n < size.patients; ++n) {
    CohortPatient& p = out[size_t(n)];
    char id[32];
    std::snprintf(id, sizeof id, "QB%06d", n + 1);
    p.patient.patient_id = id;
    p.study.study_uid = "2.25.4242." + std::to_string(seed) + "." + std::to_string(n + 1);
    p.study.patient_id = id;
    p.seed = rng.next();
    // Evenly spread: patient n is matched when it starts a new 1/matched of the list.
    p.matched = matched > 0 && (int64_t(n) * matched / size.patients) != (int64_t(n + 1) * matched / size.patients);
    if (p.matched) {
      draw_matched(p, rng);
    } else {
      do draw_background(p, rng);
      while (near_filter(p));
    }
  }
  return out;
}

std::vector<CohortStructure> matched_structures(const CohortPatient& p, const QueryCohortSize& size) {
  Rng rng(p.seed);
  const std::vector<Placed> placed = placements(p, rng);
  std::vector<CohortStructure> out;
  for (size_t i = 0; i < placed.size(); ++i) {
    Perturbation bump;
    for (int k = 0; k < 4; ++k) {
      bump.amplitude[k] = rng.uniform(0.0, 0.06);
      bump.phase[k] = rng.uniform(0, 6.28);
      bump.order[k] = rng.integer(1, 3);
    }
    const int triangles = rng.integer(size.min_triangles, size.max_triangles);
    out.push_back({kAnatomy[i / 2].name, i % 2 == 0 ? "L" : "R", deformed_ellipsoid(placed[i], triangles, bump)});
  }
  return out;
}

Image matched_image(const CohortPatient& p, const QueryCohortSize& size) {
  Rng rng(p.seed);  // the same draws as matched_structures, so the blobs sit on the structures
  const std::vector<Placed> placed = placements(p, rng);
  const double phase = Rng(p.seed ^ 0x5eedULL).uniform(0, 6.28);
  Image image;
  ImageGeometry& g = image.geometry;
  g.dims = size.image_dims;
  g.spacing_mm = {2, 2, 2};
  for (int a = 0; a < 3; ++a) g.origin_mm[a] = -double(g.dims[a] - 1);  // centred on the origin
  image.voxels.resize(size_t(g.voxel_count()));
  size_t index = 0;
  for (int64_t k = 0; k < g.dims[2]; ++k) {
    for (int64_t j = 0; j < g.dims[1]; ++j) {
      for (int64_t i = 0; i < g.dims[0]; ++i) {
        const Vec3 x = g.index_to_physical({double(i), double(j), double(k)});
        double value = 300 + 40 * std::sin(x[0] / 19 + phase) * std::cos(x[1] / 27) + 0.3 * x[2];
        for (const Placed& s : placed) {
          double d2 = 0;
          for (int a = 0; a < 3; ++a) {
            const double t = (x[a] - s.centre_mm[a]) / s.semi_axes_mm[a];
            d2 += t * t;
          }
          // ~brightness inside, falling to ~0 within a few mm outside.
          value += s.brightness / (1 + std::exp((std::sqrt(d2) - 1.15) * 7));
        }
        image.voxels[index++] = float(value);
      }
    }
  }
  return image;
}

BackgroundStructure background_structure(const CohortPatient& p, const QueryCohortSize& size) {
  Rng rng(p.seed);
  const int blob = rng.integer(0, std::max(1, size.background_blobs) - 1);
  return {blob, kAnatomy[blob % 5].name, blob % 10 < 5 ? "L" : "R"};
}

TriangleMesh background_surface(int blob) {
  const Anatomy& a = kAnatomy[blob % 5];
  Rng rng(uint64_t(blob) * 7919 + 1);
  Placed where{a.left_centre_mm, a.semi_axes_mm, 0};
  if (blob % 10 >= 5) where.centre_mm[0] = -where.centre_mm[0];  // the right side
  Perturbation bump;
  for (int k = 0; k < 4; ++k) {
    bump.amplitude[k] = rng.uniform(0.0, 0.06);
    bump.phase[k] = rng.uniform(0, 6.28);
    bump.order[k] = rng.integer(1, 3);
  }
  return deformed_ellipsoid(where, 2000, bump);
}

db::Stage1Filter query_stage1_filter() {
  db::Stage1Filter f;
  f.sex = "F";
  f.modality = "MR";
  f.study_date_from = "20200101";
  f.study_date_to = "20231231";
  f.min_age_years = 60;
  f.max_age_years = 75;
  return f;
}

}  // namespace soiq::bench
