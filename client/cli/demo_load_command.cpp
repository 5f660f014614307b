#include "client/cli/demo_load_command.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/interrupt.h"
#include "client/cli/precompute_wait.h"
#include "client/cli/progress_bar.h"
#include "client/cli/quiet.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "client/cohort/synthetic_cohort.h"
#include "core/io/write_image.h"
#include "core/io/write_mesh.h"

namespace soiq::cli {

namespace {

struct DemoArgs {
  int patients = 20;
  int seed = 1;
};

Result<DemoArgs> parse_demo_load_args(int argc, char** argv) {
  DemoArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg != "--patients" && arg != "--seed") return invalid_argument("unexpected argument '" + arg + "'");
    SOIQ_ASSIGN_OR_RETURN(const std::string v, option_value(argc, argv, i));
    if (arg == "--patients") {
      SOIQ_ASSIGN_OR_RETURN(a.patients, parse_int(v, arg, 1, 1000));
    } else {
      SOIQ_ASSIGN_OR_RETURN(a.seed, parse_int(v, arg, 0, 1 << 30));
    }
  }
  return a;
}

// A private temporary folder, removed when the command ends.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "soiq-demo-XXXXXX").string();
    if (mkdtemp(pattern.data())) path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    if (!path_.empty()) std::filesystem::remove_all(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Uploads one patient's image and structures, then prints its line (the bar cleared first).
Status load_patient(const client::Client& c, const cohort::CohortConfig& config, const cohort::SyntheticPatient& p,
                    const std::string& dir, size_t& structures, ProgressBar& bar) {
  const cohort::Demographics& d = p.demographics;
  soiq::v1::Patient patient;
  patient.set_patient_id(p.patient_id);
  patient.set_sex(d.sex);
  patient.set_birth_date(d.birth_date);
  soiq::v1::Study study;
  study.set_study_uid(p.study_uid);
  study.set_patient_id(p.patient_id);
  study.set_study_date(d.study_date);
  study.set_description(d.study_description);
  study.set_modality(d.modality);

  soiq::v1::UploadImageHeader image;
  *image.mutable_patient() = patient;
  *image.mutable_study() = study;
  image.set_series_uid(p.series_uid);
  image.set_modality(d.modality);
  const std::string image_path = dir + "/" + p.patient_id + ".nii.gz";
  const Image mr = cohort::synthetic_image(config, p);
  SOIQ_RETURN_IF_ERROR(write_image(mr, image_path));
  SOIQ_RETURN_IF_ERROR(c.upload_image(image, image_path).status());

  int64_t first = 0, last = 0;
  const std::vector<cohort::SyntheticStructure> meshes = cohort::synthetic_structures(config.structures, p);
  for (const cohort::SyntheticStructure& s : meshes) {
    soiq::v1::UploadSurfaceHeader header;
    *header.mutable_patient() = patient;
    *header.mutable_study() = study;
    header.set_structure_name(s.name);
    header.set_laterality(s.laterality);
    const std::string mesh_path = dir + "/" + p.patient_id + "_" + s.name + "_" + s.laterality + ".stl";
    SOIQ_RETURN_IF_ERROR(write_mesh(s.surface, mesh_path));
    SOIQ_ASSIGN_OR_RETURN(const soiq::v1::UploadSurfaceResponse r, c.upload_surface(header, mesh_path));
    last = r.structure().id();
    if (first == 0) first = last;
  }
  structures += meshes.size();
  if (quiet()) return ok_status();
  bar.clear();
  std::printf("%s  %s  born %s  MR %s: image %lldx%lldx%lld, %zu structures (ids %lld-%lld)\n", p.patient_id.c_str(),
              d.sex.c_str(), d.birth_date.c_str(), d.study_date.c_str(), (long long)mr.geometry.dims[0],
              (long long)mr.geometry.dims[1], (long long)mr.geometry.dims[2], meshes.size(), (long long)first,
              (long long)last);
  std::fflush(stdout);
  return ok_status();
}

Status demo_load(const DemoArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  // Fail fast, before generating anything, when the server is not there.
  SOIQ_RETURN_IF_ERROR(c.server_info().status());
  const TempDir dir;
  if (dir.path().empty()) return internal_error("cannot create a temporary folder for the demo files");
  const auto t0 = std::chrono::steady_clock::now();
  // Meshes and images are made one patient at a time, as they are sent.
  const cohort::CohortConfig config = cohort::demo_cohort_config();
  const std::vector<cohort::SyntheticPatient> people = cohort::synthetic_patients(config, a.patients, uint64_t(a.seed));
  size_t structures = 0, loaded = 0;
  // Ctrl-C stops between two patients, so none is left with part of its structures; the calls are
  // not cancelled (a patient takes a fraction of a second), and a second Ctrl-C ends at once.
  const InterruptScope interrupt;
  ProgressBar bar;
  for (const cohort::SyntheticPatient& p : people) {
    if (interrupt.interrupted()) break;
    bar.update("patients", int64_t(loaded), int64_t(people.size()));
    const Status s = load_patient(c, config, p, dir.path(), structures, bar);
    if (!s.ok()) return s;
    ++loaded;
  }
  bar.clear();
  if (interrupt.interrupted()) {
    return interrupted_by_user(std::to_string(loaded) + " of " + std::to_string(people.size()) +
                               " patients were loaded, each whole (" + std::to_string(structures) + " structures)");
  }
  const auto t1 = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(t1 - t0).count();
  // The first queries of the demo then read stored values, and stage 1 can filter on them: what a
  // user of a loaded soiqd sees.
  const Result<bool> precomputed = wait_for_precompute(c);
  if (interrupt.interrupted()) return interrupted_by_user("the patients were loaded; soiqd goes on precomputing");
  SOIQ_RETURN_IF_ERROR(precomputed.status());
  const double p = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  if (quiet()) return ok_status();
  std::printf("\nloaded %zu patients, %zu MR images, %zu structures into soiqd at %s in %.1f s\n", people.size(),
              people.size(), structures, c.address().c_str(), s);
  if (*precomputed) std::printf("precomputed their default features in %.1f s more\n", p);
  std::printf(
      "try:\n"
      "  soiq ls structures --name hippocampus\n"
      "  soiq query --name hippocampus --min-age 60 --select voxel_volume_mm3 --order-by voxel_volume_mm3\n"
      "  soiq query --where 'voxel_volume_mm3>4000' --select sphericity\n"
      "  soiq query --name amygdala --sex F --series-modality MR --where 'mean[inside,MR]>200' "
      "--select 'mean[shell:3,MR]'\n"
      "  soiq query --name caudate --laterality L --select 'asym(voxel_volume_mm3)' --order-by "
      "'asym(voxel_volume_mm3)' --desc --limit 5\n");
  return ok_status();
}

}  // namespace

int run_demo_load_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_command("demo-load", parse_demo_load_args(argc, argv),
                     [&](const DemoArgs& a) { return demo_load(a, remote); });
}

}  // namespace soiq::cli
