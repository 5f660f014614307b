#include "client/cli/compare_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/exit_code.h"
#include "core/base/run_length_volume.h"
#include "core/io/read_image.h"

namespace soiq::cli {

namespace {

Result<RunLengthVolume> load(const std::string& path, int label) {
  SOIQ_ASSIGN_OR_RETURN(Image image, read_image(path));
  return from_mask(mask_from_image(image, label));
}

Status compare_files(const std::string& a_path, const std::string& b_path, int label_a, int label_b) {
  SOIQ_ASSIGN_OR_RETURN(RunLengthVolume a, load(a_path, label_a));
  SOIQ_ASSIGN_OR_RETURN(RunLengthVolume b, load(b_path, label_b));
  SOIQ_ASSIGN_OR_RETURN(VolumeComparison c, compare(a, b));
  std::printf("%s: IoU %.6f, Dice %.6f, %lld voxels in A, %lld in B, %lld only in A, %lld only in B\n",
              c.only_a + c.only_b == 0 ? "identical" : "different", c.iou(), c.dice(), (long long)c.count_a,
              (long long)c.count_b, (long long)c.only_a, (long long)c.only_b);
  return ok_status();
}

}  // namespace

namespace {

struct CompareArgs {
  std::string files[2];
  int labels[2] = {-1, -1};
};

Result<CompareArgs> parse_compare_args(int argc, char** argv) {
  CompareArgs a;
  int n_files = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--label-a" || arg == "--label-b") && i + 1 < argc) {
      SOIQ_ASSIGN_OR_RETURN(a.labels[arg == "--label-a" ? 0 : 1], parse_int(argv[++i], arg, 0, 1 << 30));
    } else if (!arg.empty() && arg[0] != '-' && n_files < 2) {
      a.files[n_files++] = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (n_files != 2) return invalid_argument("needs two masks: soiq compare MASK_A MASK_B");
  return a;
}

}  // namespace

int run_compare_command(int argc, char** argv) {
  return run_command("compare", parse_compare_args(argc, argv), [](const CompareArgs& a) {
    return compare_files(a.files[0], a.files[1], a.labels[0], a.labels[1]);
  });
}

}  // namespace soiq::cli
