// soiq-bench: the paper's simulated models and conversion timings side by side with VTK, ITK, CGAL and
// OpenVDB.
//   soiq-bench simgen  --out DIR [--spacing S]
//   soiq-bench convert MESH --reference IMAGE --method M [--runs N] [--threads T] [--pin CPU] [--json] [-o OUT]
//   soiq-bench table5  --models DIR [--runs N] [--threads T] [--pin CPU]
//   soiq-bench table7  [--runs N] [--pin CPU]
//   soiq-bench scaling [--runs N] [--threads T] [--pin CPU]
//   soiq-bench cpu-probe [--runs N]
//   soiq-bench floor   --models DIR [--names SM1,SM6,SM11] [--runs N] [--pin CPU]
//   soiq-bench features --models DIR [--sts DIR] [--runs N]
//   soiq-bench coverage --models DIR [--sts DIR] [--runs N] [--pin CPU]
//   soiq-bench query [--small] [--dir DIR] [--soiqd PATH] [--workers N] [--runs N] [--seconds S]
//   soiq-bench codec [--runs N] [--label LABEL_IMAGE] [--image IMAGE] [--decode-only]
//   soiq-bench import DICOM_DIR... [--runs N] [--soiqd PATH]
//   soiq-bench pacs DICOM_DIR --patient ID [--runs N] [--soiqd PATH]
//                    [--patients N] [--matched N]
//   soiq-bench viewer [--runs N] [--soiqd PATH]
// Every subcommand takes --cpu-level x86-64|x86-64-v2|x86-64-v3: soiq's kernels run at most at that
// level (core/base/cpu_level.h), to compare the levels within one binary.
// Exit codes: 0 ok, 2 usage or invalid argument, 1 anything else.

#include <cstdio>
#include <optional>
#include <string>

#include "bench/cli_args.h"
#include "bench/convert_bench.h"
#include "bench/coverage_bench.h"
#include "bench/cpu_probe.h"
#include "bench/dicomweb_bench.h"
#include "bench/features_bench.h"
#include "bench/floor_bench.h"
#include "bench/import_bench.h"
#include "bench/pacs_bench.h"
#include "bench/query_bench.h"
#include "bench/render_bench.h"
#include "bench/replicas_bench.h"
#include "bench/scaling.h"
#include "bench/simgen.h"
#include "bench/surface_codec_bench.h"
#include "bench/table5.h"
#include "bench/table7.h"
#include "bench/viewer_bench.h"
#include "core/base/cpu_level.h"

namespace {

int usage() {
  std::fprintf(
      stderr,
      "usage: soiq-bench simgen --out DIR [--spacing S]\n"
      "       soiq-bench convert MESH --reference IMAGE --method 1d|2d|3d|vtk-stencil|vtk-enclosed|itk|cgal|openvdb\n"
      "                  [--runs N] [--threads T] [--pin CPU] [--json] [-o OUT]\n"
      "       soiq-bench table5 --models DIR [--runs N] [--threads T] [--pin CPU]\n"
      "       soiq-bench table7 [--runs N] [--pin CPU]\n"
      "       soiq-bench scaling [--runs N] [--threads T] [--pin CPU]\n"
      "       soiq-bench cpu-probe [--runs N]\n"
      "       soiq-bench floor --models DIR [--names SM1,SM6,SM11] [--runs N] [--pin CPU]\n"
      "       soiq-bench features --models DIR [--sts DIR] [--runs N]\n"
      "       soiq-bench coverage --models DIR [--sts DIR] [--runs N] [--pin CPU]\n"
      "       soiq-bench query [--small] [--dir DIR] [--soiqd PATH] [--workers N] [--runs N] [--seconds S]\n"
      "       soiq-bench replicas [--small] [--soiqd PATH] [--workers N] [--seconds S] [--patients N] [--matched N]\n"
      "                          [--stage1-patients N]\n"
      "       soiq-bench import DICOM_DIR... [--runs N] [--soiqd PATH]\n"
      "       soiq-bench pacs DICOM_DIR --patient ID [--runs N] [--soiqd PATH]\n"
      "       soiq-bench dicomweb [--patients N] [--batch B] [--runs R] [--soiqd PATH]\n"
      "       soiq-bench render [--runs R] [--patients N] [--soiqd PATH]\n"
      "                  [--patients N] [--matched N]\n"
      "       soiq-bench viewer [--runs R] [--soiqd PATH]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace soiq::bench;
  if (argc < 2) return usage();
  const std::string command = argv[1];
  const auto args = parse_cli_args(
      argc, argv, 2,
      {"--out",       "--spacing",        "--reference", "--method",  "--runs",  "--threads", "--pin",
       "-o",          "--models",         "--sts",       "--dir",     "--soiqd", "--workers", "--seconds",
       "--patients",  "--matched",        "--label",     "--patient", "--image", "--batch",   "--names",
       "--cpu-level", "--stage1-patients"},
      {"--json", "--small", "--decode-only"});
  if (!args.ok()) {
    std::fprintf(stderr, "soiq-bench %s: %s\n", command.c_str(), args.status().message().c_str());
    return 2;
  }
  if (args->has("--cpu-level")) {
    const std::optional<soiq::CpuLevel> level = soiq::parse_cpu_level(args->get("--cpu-level", ""));
    if (!level) {
      std::fprintf(stderr, "soiq-bench %s: --cpu-level must be x86-64, x86-64-v2 or x86-64-v3\n", command.c_str());
      return 2;
    }
    soiq::cap_cpu_level(*level);
  }
  if (command == "simgen") return run_simgen(*args);
  if (command == "convert") return run_convert(*args);
  if (command == "table5") return run_table5(*args);
  if (command == "table7") return run_table7(*args);
  if (command == "scaling") return run_scaling(*args);
  if (command == "cpu-probe") return run_cpu_probe(*args);
  if (command == "floor") return run_floor_bench(*args);
  if (command == "features") return run_features_bench(*args);
  if (command == "coverage") return run_coverage_bench(*args);
  if (command == "query") return run_query_bench(*args);
  if (command == "replicas") return run_replicas_bench(*args);
  if (command == "import") return run_import_bench(*args);
  if (command == "pacs") return run_pacs_bench(*args);
  if (command == "dicomweb") return run_dicomweb_bench(*args);
  if (command == "render") return run_render_bench(*args);
  if (command == "viewer") return run_viewer_bench(*args);
  if (command == "codec") return run_surface_codec_bench(*args);
  return usage();
}
