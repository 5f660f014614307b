#include "bench/import_bench.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/clock.h"
#include "client/soiq_client.h"
#include "core/base/run_length_volume.h"
#include "core/voxelize/fill_contours.h"
#include "dicom/convert_rt_struct.h"
#include "dicom/import_dicom.h"
#include "dicom/read_rt_struct.h"
#include "tests/support/soiqd_process.h"

namespace soiq::bench {
namespace {

namespace fs = std::filesystem;

struct CaseFiles {
  std::vector<std::string> paths;
  int64_t bytes = 0;
};

CaseFiles files_under(const std::string& dir) {
  CaseFiles out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    out.paths.push_back(e.path().string());
    out.bytes += int64_t(e.file_size());
  }
  std::sort(out.paths.begin(), out.paths.end());
  return out;
}

// dcmdump over all files in one process, stdout and stderr to /dev/null; its wall time.
Result<double> dcmdump_ms(const std::vector<std::string>& paths) {
  const Clock::time_point t0 = Clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) return internal_error("fork failed");
  if (pid == 0) {
    const int null_fd = ::open("/dev/null", O_WRONLY);
    ::dup2(null_fd, 1);
    ::dup2(null_fd, 2);
    std::vector<char*> argv = {const_cast<char*>("dcmdump")};
    for (const std::string& p : paths) argv.push_back(const_cast<char*>(p.c_str()));
    argv.push_back(nullptr);
    ::execvp("dcmdump", argv.data());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return internal_error("dcmdump failed (exit " + std::to_string(WEXITSTATUS(status)) +
                          "; is DCMTK's dcmtk package installed?)");
  return ms_since(t0);
}

std::string rate(double count, double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f", count / (ms / 1000.0));
  return text;
}

std::string fixed(double x, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, x);
  return text;
}

struct RoiRow {
  std::string case_name, roi, modality, dims;
  int64_t contours = 0, voxels = 0;
  double fill_ms = 1e300, convert_ms = 1e300;
};

// Each ROI of each structure set of `imported`: fill alone, and fill + surface, best of `runs`.
Status time_rois(const std::string& case_name, const dicom::DicomImport& imported, int runs, std::vector<RoiRow>& out) {
  for (const dicom::ImportedStructureSet& set : imported.structure_sets) {
    const dicom::SeriesImage* image = imported.find_image(set.referenced_series_uid);
    if (image == nullptr) continue;
    SOIQ_ASSIGN_OR_RETURN(const dicom::RtStructureSet rs, dicom::read_rt_struct(set.path));
    const ImageGeometry& g = image->image.geometry;
    for (const dicom::RtRoi& roi : rs.rois) {
      if (roi.contours.empty()) continue;
      RoiRow row;
      row.case_name = case_name;
      row.roi = roi.name;
      row.modality = image->modality;
      row.dims = std::to_string(g.dims[0]) + "x" + std::to_string(g.dims[1]) + "x" + std::to_string(g.dims[2]);
      row.contours = int64_t(roi.contours.size());
      dicom::RtStructureSet one = rs;
      one.rois = {roi};
      for (int r = 0; r < runs; ++r) {
        Clock::time_point t0 = Clock::now();
        SOIQ_ASSIGN_OR_RETURN(const ContourFill fill, fill_contours(roi.contours, g, FillRule::kEvenOdd));
        row.fill_ms = std::min(row.fill_ms, ms_since(t0));
        row.voxels = voxel_count(fill.volume);
        t0 = Clock::now();
        SOIQ_ASSIGN_OR_RETURN(const dicom::ConvertedStructureSet converted, dicom::convert_rt_struct(one, g));
        row.convert_ms = std::min(row.convert_ms, ms_since(t0));
      }
      out.push_back(row);
    }
  }
  return ok_status();
}

Status run(const CliArgs& args) {
  if (args.positional.empty()) return invalid_argument("give one or more DICOM folders, one case each");
  SOIQ_ASSIGN_OR_RETURN(const int runs, args.get_int("--runs", 3));
  if (runs < 1) return invalid_argument("--runs must be at least 1");
  const std::string soiqd = args.get("--soiqd", SOIQD_BINARY);

  // $SOIQ_BENCH_TMP, else the system's temporary folder ($TMPDIR, else /tmp).
  const char* base = std::getenv("SOIQ_BENCH_TMP");
  std::string work =
      ((base && *base) ? fs::path(base) : fs::temp_directory_path()).string() + "/soiq-bench-import-XXXXXX";
  if (!mkdtemp(work.data())) return internal_error("cannot create a work folder (set SOIQ_BENCH_TMP)");
  testing::SoiqdProcess server(work + "/import.db", {"--workers", "2"}, soiqd);
  if (server.address().empty()) return internal_error("soiqd did not start: " + server.log());
  client::ClientOptions options;
  options.address = server.address();
  SOIQ_ASSIGN_OR_RETURN(const client::Client client, client::Client::connect(options));

  std::printf(
      "| case | files | MB | series | structures | dcmdump ms | import ms | files/s | MB/s | import / dcmdump "
      "| soiq import ms | files/s | MB/s |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::vector<RoiRow> rois;
  for (const std::string& dir : args.positional) {
    const std::string name = fs::path(dir).filename() == "dicom" ? fs::path(dir).parent_path().filename().string()
                                                                 : fs::path(dir).filename().string();
    const CaseFiles files = files_under(dir);
    if (files.paths.empty()) return invalid_argument("'" + dir + "' holds no files");
    double dump = 1e300, import = 1e300, through = 1e300;
    dicom::DicomImport last;
    int64_t structures = 0;
    for (int r = 0; r < runs; ++r) {
      SOIQ_ASSIGN_OR_RETURN(const double d, dcmdump_ms(files.paths));
      dump = std::min(dump, d);
      Clock::time_point t0 = Clock::now();
      SOIQ_ASSIGN_OR_RETURN(last, dicom::import_dicom({dir}));
      import = std::min(import, ms_since(t0));
      t0 = Clock::now();
      SOIQ_ASSIGN_OR_RETURN(const v1::ImportDicomResponse r2, client.import_dicom({dir}));
      through = std::min(through, ms_since(t0));
      structures = r2.structures_size();
    }
    const double mb = double(files.bytes) / 1e6, n = double(files.paths.size());
    std::printf("| %s | %zu | %.1f | %zu | %lld | %.0f | %.0f | %s | %s | %.1fx | %.0f | %s | %s |\n", name.c_str(),
                files.paths.size(), mb, last.images.size(), (long long)structures, dump, import,
                rate(n, import).c_str(), fixed(mb / (import / 1000.0), 1).c_str(), import / dump, through,
                rate(n, through).c_str(), fixed(mb / (through / 1000.0), 1).c_str());
    std::fflush(stdout);
    SOIQ_RETURN_IF_ERROR(time_rois(name, last, runs, rois));
  }
  std::printf("\nRT Structure Set ROIs, each on its referenced series' grid, best of %d:\n\n", runs);
  std::printf("| case | ROI | series | grid | contours | voxels | fill ms | fill + surface ms |\n");
  std::printf("|---|---|---|---|---:|---:|---:|---:|\n");
  for (const RoiRow& r : rois)
    std::printf("| %s | %s | %s | %s | %lld | %lld | %.2f | %.2f |\n", r.case_name.c_str(), r.roi.c_str(),
                r.modality.c_str(), r.dims.c_str(), (long long)r.contours, (long long)r.voxels, r.fill_ms,
                r.convert_ms);
  server.terminate();
  std::error_code ec;
  fs::remove_all(work, ec);
  return ok_status();
}

}  // namespace

int run_import_bench(const CliArgs& args) {
  const Status s = run(args);
  if (s.ok()) return 0;
  std::fprintf(stderr, "soiq-bench import: %s\n", s.message().c_str());
  return 1;
}

}  // namespace soiq::bench
