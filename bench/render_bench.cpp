#include "bench/render_bench.h"

#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench/clock.h"
#include "client/soiq_client.h"
#include "core/geometry/primitives.h"
#include "core/io/write_image.h"
#include "core/io/write_mesh.h"
#include "db/image_blob.h"
#include "db/sqlite/sqlite_store.h"
#include "tests/support/soiqd_process.h"
#include "tests/support/temp_dir.h"

namespace soiq::bench {
namespace {

void render_note(const std::string& s) { std::fprintf(stderr, "soiq-bench render: %s\n", s.c_str()); }

double render_percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

// A CT-like volume: air, an elliptic body of soft tissue (40 HU, noise of 15 HU), a bone ring.
Image synthetic_ct() {
  Image img;
  img.geometry.dims = {512, 512, 64};
  img.geometry.spacing_mm = {0.7, 0.7, 2.5};
  img.geometry.origin_mm = {-179, -179, -80};
  img.voxels.resize(size_t(512) * 512 * 64);
  uint64_t state = 12345;
  const auto noise = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double((state >> 33) % 1000) / 1000.0 - 0.5;
  };
  for (int64_t k = 0; k < 64; ++k)
    for (int64_t j = 0; j < 512; ++j)
      for (int64_t i = 0; i < 512; ++i) {
        const double x = (double(i) - 256) / 230, y = (double(j) - 256) / 170;
        const double r = x * x + y * y;
        double v = -1000;
        if (r < 1) v = 40 + 30 * noise();
        if (r > 0.8 && r < 0.9) v = 700 + 100 * noise();
        img.voxels[size_t(i + 512 * (j + 512 * k))] = float(v);
      }
  return img;
}

int render_failed(const std::string& what) {
  render_note(what);
  return 1;
}

}  // namespace

int run_render_bench(const CliArgs& args) {
  const Result<int> runs = args.get_int("--runs", 30);
  const Result<int> patients = args.get_int("--patients", 17);
  if (!runs.ok() || !patients.ok() || *runs < 2 || *patients < 1)
    return render_failed("--runs must be >= 2 and --patients >= 1");
  testing::TempDir dir;
  const std::string db_path = dir.file("render.db");
  testing::SoiqdProcess server(db_path, {"--http", "127.0.0.1:0", "--workers", "2"}, args.get("--soiqd", ""));
  if (!server.running() || server.address().empty()) return render_failed("soiqd did not start: " + server.log());
  client::ClientOptions options;
  options.address = server.address();
  Result<client::Client> connected = client::Client::connect(options);
  if (!connected.ok()) return render_failed(connected.status().to_string());
  const client::Client& c = *connected;

  // The 512 x 512 CT and a sphere in its study.
  const std::string image_path = dir.file("ct.nii.gz");
  if (Status s = write_image(synthetic_ct(), image_path); !s.ok()) return render_failed(s.to_string());
  v1::UploadImageHeader image_header;
  image_header.mutable_patient()->set_patient_id("RENDER");
  image_header.mutable_study()->set_study_uid("2.25.4242");
  image_header.set_series_uid("2.25.4243");
  image_header.set_modality("CT");
  if (auto r = c.upload_image(image_header, image_path); !r.ok()) return render_failed(r.status().to_string());
  const std::string mesh_path = dir.file("sphere.stl");
  if (Status s = write_mesh(uv_sphere({20, -10, 0}, 15, 48, 96), mesh_path); !s.ok())
    return render_failed(s.to_string());
  v1::UploadSurfaceHeader surface_header;
  *surface_header.mutable_patient() = image_header.patient();
  *surface_header.mutable_study() = image_header.study();
  surface_header.set_structure_name("sphere");
  Result<v1::UploadSurfaceResponse> up = c.upload_surface(surface_header, mesh_path);
  if (!up.ok()) return render_failed(up.status().to_string());

  v1::RenderRequest request;
  request.set_structure_id(up->structure().id());
  const std::string out = dir.file("slice.png");
  Clock::time_point start = Clock::now();
  Result<v1::RenderInfo> first = c.render(request, out);
  const double cold_ms = ms_since(start);
  if (!first.ok()) return render_failed(first.status().to_string());
  std::vector<double> render_ms;
  for (int r = 0; r < *runs; ++r) {
    start = Clock::now();
    if (auto again = c.render(request, out); !again.ok()) return render_failed(again.status().to_string());
    render_ms.push_back(ms_since(start));
  }
  // The same image read from the same store file, in this process.
  Result<std::unique_ptr<db::SqliteStore>> store = db::SqliteStore::open(db_path, {});
  if (!store.ok()) return render_failed(store.status().to_string());
  Result<db::SeriesRecord> series = (*store)->get_series("2.25.4243");
  if (!series.ok()) return render_failed(series.status().to_string());
  std::vector<double> read_ms;
  for (int r = 0; r < *runs; ++r) {
    start = Clock::now();
    Result<std::string> blob = (*store)->get_image_blob("2.25.4243");
    if (!blob.ok()) return render_failed(blob.status().to_string());
    Result<Image> image = db::decode_image(*blob, series->geometry);
    if (!image.ok()) return render_failed(image.status().to_string());
    read_ms.push_back(ms_since(start));
  }

  // The demo cohort, then a page of 100 thumbnails, 6 requests at a time.
  const std::string soiq = std::string(SOIQ_BINARY) + " --server " + server.address() + " demo-load --patients " +
                           std::to_string(*patients) + " >/dev/null";
  if (std::system(soiq.c_str()) != 0) return render_failed("soiq demo-load failed");
  httplib::Client http("127.0.0.1", server.http_port());
  const auto rows = http.Get("/soiq/v1/query?name=*&limit=100");
  if (!rows || rows->status != 200) return render_failed("the query for the page failed");
  std::vector<int64_t> ids;
  const nlohmann::json answer = nlohmann::json::parse(rows->body);
  for (const auto& row : answer["rows"]) ids.push_back(row["id"].get<int64_t>());
  const auto page = [&]() -> double {
    std::atomic<size_t> next{0};
    std::atomic<int> failures{0};
    const Clock::time_point t0 = Clock::now();
    std::vector<std::thread> browsers;
    for (int b = 0; b < 6; ++b)
      browsers.emplace_back([&] {
        httplib::Client h("127.0.0.1", server.http_port());
        for (size_t i = next++; i < ids.size(); i = next++) {
          const auto got = h.Get("/soiq/v1/structures/" + std::to_string(ids[i]) + "/thumbnail");
          if (!got || got->status != 200) ++failures;
        }
      });
    for (std::thread& t : browsers) t.join();
    return failures ? NAN : seconds_since(t0);
  };
  const double cold_page_s = page();
  const double warm_page_s = page();
  if (std::isnan(cold_page_s) || std::isnan(warm_page_s)) return render_failed("a thumbnail request failed");

  std::printf("| what | p50 | p95 | first (cold) |\n|---|---|---|---|\n");
  std::printf(
      "| `soiq render` of a 512 x 512 CT slice (Render RPC, PNG %d x %d, %lld bytes) | %.1f ms | %.1f ms | %.1f ms |\n",
      first->width(), first->height(), (long long)first->size_bytes(), render_percentile(render_ms, 0.5),
      render_percentile(render_ms, 0.95), cold_ms);
  std::printf(
      "| reading that slice from the store (its 512 x 512 x 64 image blob read and decoded, in process) | %.1f ms | "
      "%.1f ms | |\n",
      render_percentile(read_ms, 0.5), render_percentile(read_ms, 0.95));
  std::printf("| a page of %zu thumbnails over HTTP, 6 at a time, all of them | warm %.3f s | | cold %.3f s |\n",
              ids.size(), warm_page_s, cold_page_s);
  return 0;
}

}  // namespace soiq::bench
