#include "bench/coverage_accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

#include "bench/smoothed_structure.h"
#include "core/features/structure_features.h"
#include "core/geometry/primitives.h"
#include "core/geometry/surface_area_volume.h"
#include "core/io/read_image.h"
#include "core/voxelize/coverage_1d.h"
#include "core/voxelize/voxelize_1d.h"
#include "dicom/read_image_series.h"
#include "dicom/scan_dicom.h"

namespace soiq::bench {

namespace coverage_accuracy_detail {

// `n` voxels of `spacing` per side centred on `centre`, axes rotated by `direction`.
ImageGeometry grid_at(const Vec3& centre, int64_t n, const Vec3& spacing, const Mat3& direction) {
  ImageGeometry g;
  g.dims = {n, n, n};
  g.spacing_mm = spacing;
  g.direction = direction;
  Vec3 half{};
  for (int a = 0; a < 3; ++a)
    for (int r = 0; r < 3; ++r)
      half[size_t(r)] += direction[size_t(r)][size_t(a)] * spacing[size_t(a)] * double(n - 1) / 2;
  g.origin_mm = centre - half;
  return g;
}

std::map<std::string, double> features_of(const TriangleMesh& mesh, const ImageGeometry& g, const Image& image,
                                          const std::vector<std::string>& names) {
  std::map<std::string, double> out;
  auto v = voxelize_1d(mesh, g);
  if (!v.ok()) return out;
  FeatureRequest request;
  request.names = names;
  request.images = {{"image", &image}};
  auto r = structure_features({v->volume, std::make_shared<const TriangleMesh>(mesh)}, request);
  if (!r.ok()) {
    std::fprintf(stderr, "coverage: %s\n", r.status().to_string().c_str());
    return out;
  }
  for (const Feature& f : r->features) out[f.name] = f.value[0];
  return out;
}

}  // namespace coverage_accuracy_detail

using namespace coverage_accuracy_detail;

Status print_volume_accuracy() {
  const Vec3 c{10, -20, 35};
  const ImageGeometry g = grid_at(c, 34, {0.9, 1.1, 1.4}, rotation_about({0.2, 1, 0.5}, 0.3));
  const std::vector<std::pair<const char*, TriangleMesh>> shapes = {
      {"sphere r 9.3",
       transformed(uv_sphere({0, 0, 0}, 9.3, 90, 180), {1, 1, 1}, identity3(), c + Vec3{0.31, -0.17, 0.23})},
      {"ellipsoid 12.2 x 7.1 x 5.3", transformed(uv_sphere({0, 0, 0}, 1, 90, 180), {12.2, 7.1, 5.3},
                                                 rotation_about({1, 2, 3}, 0.7), c + Vec3{-0.4, 0.2, 0.1})},
      {"cube 13", transformed(box({-6.5, -6.5, -6.5}, {6.5, 6.5, 6.5}), {1, 1, 1}, rotation_about({1, 1, 0.3}, 0.5),
                              c + Vec3{0.13, 0.29, -0.37})},
  };
  std::printf("| shape (oblique, grid 0.9 x 1.1 x 1.4 mm, rotated) | exact mm3 | n=1 | n=2 | n=4 | n=8 |\n");
  std::printf("|---|---:|---:|---:|---:|---:|\n");
  for (const auto& [name, mesh] : shapes) {
    SOIQ_ASSIGN_OR_RETURN(const SurfaceAreaVolume exact, surface_area_volume(mesh));
    std::printf("| %s | %.2f |", name, exact.volume_mm3);
    for (int n : {1, 2, 4, 8}) {
      CoverageOptions o;
      o.lines_per_voxel = n;
      SOIQ_ASSIGN_OR_RETURN(const CoverageVolume v, coverage_1d(mesh, g, o));
      const double error = covered_voxels(v) * g.voxel_volume_mm3() - exact.volume_mm3;
      std::printf(" %+.3f%% |", 100 * error / exact.volume_mm3);
    }
    std::printf("\n");
  }
  return ok_status();
}

Status print_lesion_accuracy() {
  constexpr double kRadius = 5;
  struct Field {
    const char* name;
    double (*value)(const Vec3& offset);  // offset from the lesion's centre, mm
    double exact_mean;                    // over the lesion
  };
  // Linear: the mean over a ball is the value at its centre. Peaked: 1 + 10 (1 - 3/5) = 5.
  const Field fields[] = {
      {"gradient 1 + 0.5 x/mm", [](const Vec3& d) { return 1 + 0.5 * d[0]; }, 1},
      {"peaked 1 + 10 (1 - r^2/R^2)", [](const Vec3& d) { return 1 + 10 * (1 - dot(d, d) / (kRadius * kRadius)); }, 5},
  };
  std::printf(
      "| uptake | voxels | centre rule: error mean (sd) | weighted mean_w: error mean (sd) | volume error, centre "
      "rule | volume error, weighted |\n");
  std::printf("|---|---|---:|---:|---:|---:|\n");
  for (const Field& field : fields) {
    for (double s : {2.0, 4.0, 6.0}) {
      std::vector<double> plain, weighted;
      double vol_plain = 0, vol_weighted = 0;
      for (int p = 0; p < 64; ++p) {
        // Sub-voxel positions on a 4 x 4 x 4 lattice, so no two lesions sit the same way on the grid.
        const Vec3 centre{s * ((p % 4) + 0.5) / 4, s * ((p / 4 % 4) + 0.5) / 4, s * ((p / 16) + 0.5) / 4};
        const TriangleMesh lesion = uv_sphere(centre, kRadius, 60, 120);
        const int64_t n = int64_t(std::ceil(2 * (kRadius + 2 * s) / s)) | 1;
        const ImageGeometry g = grid_at({0, 0, 0}, n, {s, s, s}, identity3());
        Image uptake{g, std::vector<float>(size_t(g.voxel_count()))};
        for (int64_t v = 0; v < g.voxel_count(); ++v) {
          const Vec3 q = g.index_to_physical({double(v % n), double(v / n % n), double(v / (n * n))});
          uptake.voxels[size_t(v)] = float(field.value(q - centre));
        }
        const auto f = features_of(lesion, g, uptake, {"mean", "mean_w", "voxel_volume_mm3", "volume_w_mm3"});
        if (f.size() < 4) return internal_error("lesion features failed");
        const double mesh_volume = surface_area_volume(lesion)->volume_mm3;
        plain.push_back(f.at("mean") - field.exact_mean);
        weighted.push_back(f.at("mean_w") - field.exact_mean);
        vol_plain += std::abs(f.at("voxel_volume_mm3") - mesh_volume) / mesh_volume / 64;
        vol_weighted += std::abs(f.at("volume_w_mm3") - mesh_volume) / mesh_volume / 64;
      }
      auto mean_sd = [](const std::vector<double>& e) {
        double m = 0, m2 = 0;
        for (double x : e) m += x / double(e.size());
        for (double x : e) m2 += (x - m) * (x - m) / double(e.size());
        return std::pair{m, std::sqrt(m2)};
      };
      const auto [mp, sp] = mean_sd(plain);
      const auto [mw, sw] = mean_sd(weighted);
      std::printf("| %s | %.0f mm | %+.3f (%.3f) | %+.3f (%.3f) | %.1f%% | %.1f%% |\n", field.name, s, mp, sp, mw, sw,
                  100 * vol_plain, 100 * vol_weighted);
    }
  }
  return ok_status();
}

Status print_sts_pet_uptake(const std::string& sts_dir) {
  std::printf("| patient | PET grid | unit | volume mm3 (centre rule) | volume_w mm3 | mean | mean_w | difference |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|\n");
  std::vector<std::string> patients;
  for (const auto& entry : std::filesystem::directory_iterator(sts_dir))
    if (std::filesystem::exists(entry.path() / "CT_mask.nii.gz")) patients.push_back(entry.path().filename());
  std::sort(patients.begin(), patients.end());
  for (const std::string& patient : patients) {
    const std::string base = sts_dir + "/" + patient;
    SOIQ_ASSIGN_OR_RETURN(const Image mask, read_image(base + "/CT_mask.nii.gz"));
    SOIQ_ASSIGN_OR_RETURN(const TriangleMesh tumour, smoothed_structure(mask_from_image(mask), 100000));
    const std::string folder =
        std::filesystem::exists(base + "/dicom/PET") ? base + "/dicom/PET" : base + "/dicom_jpegls/PET";
    SOIQ_ASSIGN_OR_RETURN(const dicom::DicomScan scan, dicom::scan_dicom({folder}));
    const auto is_pet = [](const dicom::DicomSeries& s) { return s.modality == "PT"; };
    const auto series = std::find_if(scan.series.begin(), scan.series.end(), is_pet);
    if (series == scan.series.end()) return internal_error(patient + ": no PET series in " + folder);
    SOIQ_ASSIGN_OR_RETURN(const dicom::SeriesImage pet, dicom::read_image_series(*series));
    const auto f =
        features_of(tumour, pet.image.geometry, pet.image, {"mean", "mean_w", "voxel_volume_mm3", "volume_w_mm3"});
    if (f.size() < 4) return internal_error(patient + ": features failed");
    std::printf("| %s | %s | %s | %.0f | %.0f | %.3f | %.3f | %+.2f%% |\n", patient.c_str(),
                describe(pet.image.geometry).c_str(), pet.units.c_str(), f.at("voxel_volume_mm3"), f.at("volume_w_mm3"),
                f.at("mean"), f.at("mean_w"), 100 * (f.at("mean_w") - f.at("mean")) / f.at("mean"));
  }
  std::printf(
      "\nTumour surfaces from the CT masks (marching cubes, windowed-sinc smoothing, Loop subdivision to "
      ">= 100k triangles: bench/smoothed_structure.h), converted on the PET series' own grid.\n");
  return ok_status();
}

}  // namespace soiq::bench
