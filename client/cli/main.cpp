// `soiq`: the command-line client. Each command lives in its own <name>_command.cpp; the offline
// ones run core/ here, the remote ones talk to soiqd through client/soiq_client.h.
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "client/cli/compare_command.h"
#include "client/cli/convert_command.h"
#include "client/cli/demo_load_command.h"
#include "client/cli/download_command.h"
#include "client/cli/exit_code.h"
#include "client/cli/export_seg_command.h"
#include "client/cli/features_command.h"
#include "client/cli/health_command.h"
#include "client/cli/import_command.h"
#include "client/cli/info_command.h"
#include "client/cli/ls_command.h"
#include "client/cli/mesh_command.h"
#include "client/cli/pacs_command.h"
#include "client/cli/query_command.h"
#include "client/cli/remote_convert_command.h"
#include "client/cli/remote_features_command.h"
#include "client/cli/remote_options.h"
#include "client/cli/rm_command.h"
#include "client/cli/show_command.h"
#include "client/cli/structure_operand.h"
#include "client/cli/upload_command.h"
#include "client/cli/upload_image_command.h"

namespace {

constexpr const char* kHelp =
    "soiq - query medical images by the content of their structures of interest\n"
    "\n"
    "Offline commands (no server needed):\n"
    "  soiq convert MESH -o OUT.{nii.gz,nii,nrrd,mha} [--reference IMAGE | --spacing S|SX,SY,SZ [--margin N]]\n"
    "               [--robust] [--even-odd] [--threads N] [--ras]\n"
    "      surface model -> volume model (the 1D scanline method); prints one summary line\n"
    "  soiq mesh MASK -o OUT.{stl,vtk,vtp,ply,obj} [--label N]\n"
    "      mask -> surface model (marching cubes at 0.5, LPS mm, outward normals)\n"
    "  soiq features INPUT [--label N] [--reference IMAGE | --spacing S [--margin N]] [--image [NAME=]IMAGE]...\n"
    "               [--region inside|shell:R|core:R]... [--features LIST] [--format table|json|csv]\n"
    "               [--interpolation nearest|linear] [--ibsi] [--robust] [--even-odd] [--ras] [--threads N]\n"
    "      shape and intensity features of a structure (a surface model or a mask)\n"
    "  soiq features --list [--format table|csv|markdown]\n"
    "      every feature soiq computes: family, unit, what it needs, definition\n"
    "  soiq compare MASK_A MASK_B [--label-a N] [--label-b N]\n"
    "      overlap of two masks on one grid: IoU, Dice, differing voxels\n"
    "\n"
    "Remote commands (talk to soiqd):\n"
    "  soiq upload MESH --patient ID --study UID --name NAME [--laterality L|R] [--sex M|F|O]\n"
    "               [--birth-date YYYYMMDD] [--study-date YYYYMMDD] [--modality MR] [--description D]\n"
    "               [--ras] [--robust] [-q]\n"
    "      stores a surface model; prints its structure id and whether the surface was deduplicated\n"
    "  soiq upload-image IMAGE --patient ID --study UID --series UID --modality PT [--sex ..] [--birth-date ..]\n"
    "               [--study-date ..] [--description D]\n"
    "      stores an image series (.nii .nii.gz .nrrd .mha): a target grid and the image of intensity features\n"
    "  soiq import PATH... [--format table|json|csv]\n"
    "      sends DICOM files and folders (recursively) to soiqd: CT, MR and PET series become images, RT\n"
    "      Structure Set ROIs structures on their series' grid; prints what was imported, problems on stderr\n"
    "  soiq export-seg ID... -o OUT.dcm [--description TEXT]\n"
    "      imported structures as one binary DICOM SEG on the image series they were drawn on\n"
    "  soiq pacs echo | find [--level study|patient] [--patient ID] [--name NAME] [--study-date D|D1-D2]\n"
    "               [--modality CT] [--study UID] [--accession A] [--max N] [--format ..]\n"
    "             | pull (--study UID... | --patient ID) [--format ..] | push ID... [--description TEXT]\n"
    "      the PACS soiqd was started with (soiqd --pacs AE@HOST:PORT): C-ECHO, C-FIND, C-GET into soiq\n"
    "      (imported like 'soiq import', all or nothing), a SEG of structures C-STOREd back\n"
    "  soiq ls [patients|studies|structures] [--patient ID|GLOB] [--study UID] [--name GLOB] [--laterality L|R]\n"
    "               [--sex M|F|O] [--format table|json|csv] [--all | --page-size N]\n"
    "  soiq show patient ID | study UID | [structure] ID [--format text|json]\n"
    "  soiq rm structure ID | patient ID\n"
    "  soiq download ID -o OUT.{stl,obj,ply,vtk,vtp} [--ras]\n"
    "  soiq convert ID -o OUT.{nii.gz,nii,nrrd,mha} [--spacing S [--margin N] | --series UID | --series-modality M]\n"
    "               [--even-odd]\n"
    "  soiq features ID [--features LIST] [--region inside|shell:R|core:R]... [--image MODALITY|SERIES_UID]...\n"
    "               [--spacing S [--margin N] | --series UID | --series-modality M] [--interpolation nearest|linear]\n"
    "               [--format table|json|csv]\n"
    "      convert and features run on soiqd when their operand is a structure id (all digits, or id:N),\n"
    "      offline when it is a file (a file named like an id is refused as ambiguous: write ./N or id:N)\n"
    "  soiq query [--patient GLOB] [--sex M|F|O] [--min-age Y] [--max-age Y] [--birth-date-from D] [--birth-date-to "
    "D]\n"
    "               [--study-date-from D] [--study-date-to D] [--modality M] [--description GLOB] [--name GLOB]\n"
    "               [--laterality L|R] [--where 'FEATURE OP NUMBER']... [--select FEATURE]...\n"
    "               [--order-by FEATURE [--desc]] [--limit N] [--spacing S | --series-modality M]\n"
    "               [--interpolation nearest|linear] [--format table|json|csv]\n"
    "      the two-stage query: stage 1 filters the records, stage 2 the features (computed on demand);\n"
    "      FEATURE is NAME, NAME[REGION], NAME[REGION,IMAGE], NAME[,IMAGE] or asym(FEATURE), REGION is\n"
    "      inside, shell:R or core:R (mm), IMAGE a modality or series uid; OP is < <= > >= == !=.\n"
    "      e.g. --where 'voxel_volume_mm3>50000' --where 'mean[shell:5,PT]>2.5' --order-by 'mean[inside,PT]' --desc\n"
    "      rows on stdout; a progress bar (on a terminal) and a summary line on stderr; Ctrl-C cancels\n"
    "  soiq info [--format text|json] [--features]\n"
    "      soiqd's version, limits and record counts\n"
    "  soiq health\n"
    "      asks soiqd's standard health service (grpc.health.v1): SERVING (exit 0) or not (exit 6)\n"
    "  soiq demo-load [--patients N] [--seed S]\n"
    "      loads a synthetic cohort (default 20 patients: MR image, hippocampus/amygdala/caudate L and R)\n"
    "\n"
    "Connection options, for every remote command, before or after the command name:\n"
    "  --server ADDRESS     soiqd's address: HOST[:PORT], [IPV6]:PORT, http://HOST:PORT (plaintext),\n"
    "                       https://HOST:PORT (TLS), unix:PATH (default $SOIQ_SERVER, else 127.0.0.1:50051;\n"
    "                       default port 50051)\n"
    "  --token-file F       send the bearer token in F (authorization: Bearer ...)\n"
    "  --tls-ca F           use TLS and verify soiqd's certificate against the PEM roots in F\n"
    "  --timeout SECONDS    deadline of each call (default 30 s; 600 s for uploads, conversions, queries)\n"
    "\n"
    "Exit codes: 0 ok, 1 other, 2 invalid argument or usage, 3 not found, 4 already exists or failed\n"
    "precondition, 5 resource exhausted, 6 unavailable, deadline or cancelled, 7 unauthenticated or\n"
    "permission denied, 8 partial query answer (some candidates skipped; the summary says why). Errors are\n"
    "one line on stderr.\n";

// Options of convert and features that take a value: the operand is the first other argument.
const std::vector<std::string> kConvertValueOptions = {"-o",       "--output",  "--reference", "--spacing",
                                                       "--margin", "--threads", "--series",    "--series-modality"};
const std::vector<std::string> kFeaturesValueOptions = {
    "--label",  "--reference", "--spacing", "--margin",        "--threads", "--image",
    "--region", "--features",  "--format",  "--interpolation", "--series",  "--series-modality"};

}  // namespace

namespace {

int dispatch(int argc, char** argv);

}  // namespace

// Estimates refuse what cannot fit before it is allocated; this is the last line for what they do
// not cover (a bad_alloc must still end in one readable line and the RESOURCE_EXHAUSTED code).
int main(int argc, char** argv) {
  try {
    return dispatch(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "soiq: out of memory: the input needs more than this machine can give (try a coarser --spacing "
                 "or a smaller --margin)\n");
    return soiq::cli::exit_code(soiq::resource_exhausted(""));
  }
}

namespace {

int dispatch(int argc, char** argv) {
  using namespace soiq::cli;
  const soiq::Result<soiq::client::ClientOptions> remote = take_remote_options(argc, argv);
  if (!remote.ok()) {
    std::fprintf(stderr, "soiq: %s (usage: soiq help)\n", remote.status().message().c_str());
    return kExitUsage;
  }
  if (argc < 2 || !std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    std::fputs(kHelp, argc < 2 ? stderr : stdout);
    return argc < 2 ? kExitUsage : 0;
  }
  const std::string command = argv[1];
  const int n = argc - 1;
  char** args = argv + 1;
  if (command == "convert" || command == "features") {
    const bool convert = command == "convert";
    const soiq::Result<OperandKind> kind =
        structure_operand_kind(first_operand(n, args, convert ? kConvertValueOptions : kFeaturesValueOptions));
    if (!kind.ok()) {
      std::fprintf(stderr, "soiq %s: %s\n", command.c_str(), kind.status().message().c_str());
      return exit_code(kind.status());
    }
    if (*kind == OperandKind::kStored) {
      return convert ? run_remote_convert_command(n, args, *remote) : run_remote_features_command(n, args, *remote);
    }
    return convert ? run_convert_command(n, args) : run_features_command(n, args);
  }
  if (command == "compare") return run_compare_command(n, args);
  if (command == "mesh") return run_mesh_command(n, args);
  if (command == "upload") return run_upload_command(n, args, *remote);
  if (command == "upload-image") return run_upload_image_command(n, args, *remote);
  if (command == "import") return run_import_command(n, args, *remote);
  if (command == "ls") return run_ls_command(n, args, *remote);
  if (command == "show") return run_show_command(n, args, *remote);
  if (command == "rm") return run_rm_command(n, args, *remote);
  if (command == "download") return run_download_command(n, args, *remote);
  if (command == "query") return run_query_command(n, args, *remote);
  if (command == "info") return run_info_command(n, args, *remote);
  if (command == "health") return run_health_command(n, args, *remote);
  if (command == "export-seg") return run_export_seg_command(n, args, *remote);
  if (command == "pacs") return run_pacs_command(n, args, *remote);
  if (command == "demo-load") return run_demo_load_command(n, args, *remote);
  std::fprintf(stderr, "soiq: unknown command '%s' (try 'soiq help')\n", command.c_str());
  return kExitUsage;
}

}  // namespace
