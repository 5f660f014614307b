#include "tests/integration/cohort.h"

#include "core/io/write_image.h"
#include "core/io/write_mesh.h"

namespace soiq::testing {

cohort::CohortConfig test_cohort_config() {
  cohort::CohortConfig c = cohort::demo_cohort_config();
  c.id_prefix = "C";
  c.id_digits = 2;
  c.uid_root = "2.25.77";
  c.structures.kinds = 2;  // hippocampus and amygdala
  c.structures.min_triangles = c.structures.max_triangles = 1600;
  return c;
}

Cohort load_cohort(ServiceTest&, client::Client& c, TempDir& dir, int patients) {
  const cohort::CohortConfig config = test_cohort_config();
  Cohort out;
  for (const cohort::SyntheticPatient& p : cohort::synthetic_patients(config, patients, kCohortSeed)) {
    const cohort::Demographics& d = p.demographics;
    auto fill = [&](auto& header) {
      header.mutable_patient()->set_patient_id(p.patient_id);
      header.mutable_patient()->set_sex(d.sex);
      header.mutable_patient()->set_birth_date(d.birth_date);
      header.mutable_study()->set_study_uid(p.study_uid);
      header.mutable_study()->set_study_date(d.study_date);
      header.mutable_study()->set_age_years(p.age_years);
      header.mutable_study()->set_modality(d.modality);
    };
    const std::string image_path = dir.file(p.patient_id + "_mr.nii.gz");
    Status s = write_image(cohort::synthetic_image(config, p), image_path);
    EXPECT_TRUE(s.ok()) << s.to_string();
    v1::UploadImageHeader ih;
    fill(ih);
    ih.set_series_uid(p.series_uid);
    ih.set_modality(d.modality);
    Result<v1::UploadImageResponse> ir = c.upload_image(ih, image_path);
    EXPECT_TRUE(ir.ok()) << ir.status().to_string();

    for (const cohort::SyntheticStructure& m : cohort::synthetic_structures(config.structures, p)) {
      const std::string path = dir.file(p.patient_id + "_" + m.name + m.laterality + ".vtp");
      s = write_mesh(m.surface, path);
      EXPECT_TRUE(s.ok()) << s.to_string();
      v1::UploadSurfaceHeader h;
      fill(h);
      h.set_structure_name(m.name);
      h.set_laterality(m.laterality);
      Result<v1::UploadSurfaceResponse> r = c.upload_surface(h, path);
      EXPECT_TRUE(r.ok()) << r.status().to_string();
      if (!r.ok()) continue;
      out.structures.push_back({r->structure().id(), p.patient_id, p.study_uid, m.name, m.laterality, d.sex,
                                double(p.age_years), path, image_path});
    }
  }
  return out;
}

}  // namespace soiq::testing
