#include "bench/query_load.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <mutex>
#include <thread>

#include "bench/clock.h"
#include "client/soiq_client.h"
#include "core/io/write_image.h"
#include "core/io/write_mesh.h"
#include "db/sqlite/sqlite_store.h"
#include "db/surface_blob.h"
#include "server/api/proto_records.h"

namespace soiq::bench {
namespace {

struct PreparedPatient {
  const CohortPatient* patient = nullptr;
  std::string image_path;
  std::vector<std::pair<cohort::SyntheticStructure, std::string>> surfaces;  // mesh freed, name kept; path
  int64_t triangles = 0;
};

// Writes one matched patient's files: its image as .nii, its surfaces as binary .ply.
Result<PreparedPatient> prepare(const CohortPatient& p, const QueryCohortSize& size, const std::string& dir) {
  PreparedPatient out;
  out.patient = &p;
  out.image_path = dir + "/" + p.person.patient_id + ".nii";
  SOIQ_RETURN_IF_ERROR(write_image(matched_image(p, size), out.image_path));
  for (cohort::SyntheticStructure& s : matched_structures(p, size)) {
    const std::string path = dir + "/" + p.person.patient_id + "_" + s.name + "_" + s.laterality + ".ply";
    SOIQ_RETURN_IF_ERROR(write_mesh(s.surface, path));
    out.triangles += int64_t(s.surface.triangles.size());
    s.surface = {};
    out.surfaces.emplace_back(std::move(s), path);
  }
  return out;
}

// Runs fn(i) for i in [0, n) on `threads` threads; the first error wins.
Status parallel(size_t n, int threads, const std::function<Status(size_t)>& fn) {
  std::atomic<size_t> next{0};
  std::mutex mutex;
  Status first = ok_status();
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, threads); ++t) {
    pool.emplace_back([&] {
      for (size_t i = next++; i < n; i = next++) {
        Status s = fn(i);
        if (!s.ok()) {
          std::lock_guard lock(mutex);
          if (first.ok()) first = s;
          return;
        }
      }
    });
  }
  for (std::thread& t : pool) t.join();
  return first;
}

}  // namespace

namespace {
Result<LoadFigures> load_background_into(const std::string& db_path, const std::vector<CohortPatient>& cohort,
                                         const QueryCohortSize& size);
}  // namespace

Result<LoadFigures> load_background(const std::string& db_path, const std::vector<CohortPatient>& cohort,
                                    const QueryCohortSize& size) {
  std::string shm = "/dev/shm/soiq-bench-load-XXXXXX";
  if (!mkdtemp(shm.data())) return load_background_into(db_path, cohort, size);  // no tmpfs: fsync'd, slower
  Result<LoadFigures> background = load_background_into(shm + "/cohort.db", cohort, size);
  std::error_code ec;
  if (background.ok())
    std::filesystem::copy_file(shm + "/cohort.db", db_path, std::filesystem::copy_options::overwrite_existing, ec);
  std::filesystem::remove_all(shm);
  if (ec) return internal_error("cannot copy the loaded cohort to " + db_path + ": " + ec.message());
  return background;
}

namespace {

Result<LoadFigures> load_background_into(const std::string& db_path, const std::vector<CohortPatient>& cohort,
                                         const QueryCohortSize& size) {
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqliteStore> store, db::SqliteStore::open(db_path, {}));
  std::vector<db::EncodedSurface> blobs;
  for (int b = 0; b < std::max(1, size.background_blobs); ++b) {
    SOIQ_ASSIGN_OR_RETURN(db::EncodedSurface e, db::encode_surface(background_surface(b)));
    blobs.push_back(std::move(e));
  }
  LoadFigures f;
  const Clock::time_point t0 = Clock::now();
  for (const CohortPatient& p : cohort) {
    if (p.matched) continue;
    const BackgroundStructure b = background_structure(p, size);
    db::NewStructure s;
    s.patient = patient_record(p);
    s.study = study_record(p);
    s.name = b.name;
    s.laterality = b.laterality;
    s.surface = blobs[size_t(b.blob)].info;
    s.surface_blob = blobs[size_t(b.blob)].blob;
    Result<db::AddedStructure> added = store->add_structure(s);
    if (!added.ok())
      return Status(added.status().code(), "patient " + p.person.patient_id + ": " + added.status().message());
    ++f.patients;
    ++f.structures;
  }
  f.seconds = seconds_since(t0);
  return f;
}

}  // namespace

Result<LoadFigures> upload_matched(const std::string& address, const std::string& work_dir,
                                   const std::vector<CohortPatient>& cohort, const QueryCohortSize& size, int threads) {
  std::vector<const CohortPatient*> matched;
  for (const CohortPatient& p : cohort)
    if (p.matched) matched.push_back(&p);
  std::vector<PreparedPatient> prepared(matched.size());
  SOIQ_RETURN_IF_ERROR(parallel(matched.size(), 2, [&](size_t i) -> Status {
    SOIQ_ASSIGN_OR_RETURN(prepared[i], prepare(*matched[i], size, work_dir));
    return ok_status();
  }));

  client::ClientOptions options;
  options.address = address;
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, client::Client::connect(options));
  LoadFigures f;
  std::mutex mutex;
  auto file_bytes = [](const std::string& path) { return int64_t(std::filesystem::file_size(path)); };
  Clock::time_point t0 = Clock::now();
  SOIQ_RETURN_IF_ERROR(parallel(prepared.size(), threads, [&](size_t i) -> Status {
    const PreparedPatient& p = prepared[i];
    v1::UploadImageHeader h;
    *h.mutable_patient() = server::to_proto(patient_record(*p.patient));
    *h.mutable_study() = server::to_proto(study_record(*p.patient));
    h.set_series_uid(p.patient->person.series_uid);
    h.set_modality("MR");
    SOIQ_RETURN_IF_ERROR(c.upload_image(h, p.image_path).status());
    std::lock_guard lock(mutex);
    ++f.images;
    f.image_bytes += file_bytes(p.image_path);
    return ok_status();
  }));
  f.image_seconds = seconds_since(t0);
  t0 = Clock::now();
  SOIQ_RETURN_IF_ERROR(parallel(prepared.size(), threads, [&](size_t i) -> Status {
    const PreparedPatient& p = prepared[i];
    for (const auto& [s, path] : p.surfaces) {
      v1::UploadSurfaceHeader h;
      *h.mutable_patient() = server::to_proto(patient_record(*p.patient));
      *h.mutable_study() = server::to_proto(study_record(*p.patient));
      h.set_structure_name(s.name);
      h.set_laterality(s.laterality);
      Result<v1::UploadSurfaceResponse> r = c.upload_surface(h, path);
      if (!r.ok()) return Status(r.status().code(), path + ": " + r.status().message());
      if (r->defects().rfind("0 boundary edges, 0 non-manifold edges, 0 degenerate", 0) != 0)
        return internal_error(path + ": the server reports defects: " + r->defects());
      std::lock_guard lock(mutex);
      ++f.structures;
      f.surface_bytes += file_bytes(path);
    }
    std::lock_guard lock(mutex);
    ++f.patients;
    f.triangles += p.triangles;
    return ok_status();
  }));
  f.surface_seconds = seconds_since(t0);
  f.seconds = f.image_seconds + f.surface_seconds;
  for (const PreparedPatient& p : prepared) {
    std::error_code ec;
    std::filesystem::remove(p.image_path, ec);
    for (const auto& [s, path] : p.surfaces) std::filesystem::remove(path, ec);
  }
  return f;
}

}  // namespace soiq::bench
