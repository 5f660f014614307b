#include "tests/integration/cohort.h"

#include "core/geometry/primitives.h"
#include "core/io/write_image.h"
#include "core/io/write_mesh.h"

namespace soiq::testing {

Image cohort_image(int patient) {
  Image img;
  img.geometry.dims = {64, 64, 48};
  img.geometry.spacing_mm = {2, 2, 2};
  img.geometry.origin_mm = {-63, -63, -47};
  img.voxels.resize(size_t(img.geometry.voxel_count()));
  size_t n = 0;
  for (int k = 0; k < 48; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i) {
        const Vec3 p = img.geometry.index_to_physical({double(i), double(j), double(k)});
        img.voxels[n++] = float(100 + p[0] + 0.5 * p[1] + p[2] * p[2] / 20 + 10 * patient);
      }
  return img;
}

Cohort load_cohort(ServiceTest&, client::Client& c, TempDir& dir, int patients) {
  Cohort cohort;
  for (int p = 0; p < patients; ++p) {
    char id[16];
    std::snprintf(id, sizeof id, "C%02d", p);
    const std::string patient = id, study = std::string("1.2.3.") + std::to_string(p);
    const std::string sex = p % 2 == 0 ? "F" : "M";
    const double age = 30 + 3 * p;
    auto fill = [&](auto& header) {
      header.mutable_patient()->set_patient_id(patient);
      header.mutable_patient()->set_sex(sex);
      header.mutable_study()->set_study_uid(study);
      header.mutable_study()->set_study_date("2024010" + std::to_string(1 + p % 9));
      header.mutable_study()->set_age_years(age);
      header.mutable_study()->set_modality("MR");
    };
    const std::string image_path = dir.file(patient + "_mr.nii.gz");
    Status s = write_image(cohort_image(p), image_path);
    EXPECT_TRUE(s.ok()) << s.to_string();
    v1::UploadImageHeader ih;
    fill(ih);
    ih.set_series_uid(study + ".1");
    ih.set_modality("MR");
    Result<v1::UploadImageResponse> ir = c.upload_image(ih, image_path);
    EXPECT_TRUE(ir.ok()) << ir.status().to_string();
    cohort.image_paths.push_back(image_path);

    const struct {
      const char* name;
      double radius, x, z;
    } shapes[] = {{"Hippocampus", 6 + 0.5 * p, 22, -5}, {"Amygdala", 4 + 0.25 * (p % 5), 16, 8}};
    for (const auto& shape : shapes) {
      for (const char* side : {"L", "R"}) {
        // L is the patient's left: +x in LPS. The right one is a little smaller for odd patients.
        const bool left = side[0] == 'L';
        const double r = shape.radius * (left || p % 2 == 0 ? 1.0 : 0.9);
        const TriangleMesh m = uv_sphere({left ? shape.x : -shape.x, 3.0, shape.z}, r, 20, 40);
        const std::string path = dir.file(patient + "_" + shape.name + side + ".vtp");
        s = write_mesh(m, path);
        EXPECT_TRUE(s.ok()) << s.to_string();
        v1::UploadSurfaceHeader h;
        fill(h);
        h.set_structure_name(shape.name);
        h.set_laterality(side);
        Result<v1::UploadSurfaceResponse> r2 = c.upload_surface(h, path);
        EXPECT_TRUE(r2.ok()) << r2.status().to_string();
        if (!r2.ok()) continue;
        cohort.structures.push_back({r2->structure().id(), patient, study, shape.name, side, sex, age, path});
      }
    }
  }
  return cohort;
}

}  // namespace soiq::testing
