#include "client/cli/compare_command.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "client/cli/exit_code.h"
#include "core/io/read_image.h"
#include "core/run_length_volume.h"

namespace soiq::cli {

namespace {

constexpr const char* kUsage = "usage: soiq compare MASK_A MASK_B [--label-a N] [--label-b N]";

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

int run_compare_command(int argc, char** argv) {
  std::string files[2];
  int labels[2] = {-1, -1};
  int n_files = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--label-a" || arg == "--label-b") && i + 1 < argc) {
      char* end = nullptr;
      const long v = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || v < 0 || v > 1000000) {
        std::fprintf(stderr, "soiq compare: %s must be a label number >= 0\n%s\n", arg.c_str(), kUsage);
        return 2;
      }
      labels[arg == "--label-a" ? 0 : 1] = int(v);
    } else if (!arg.empty() && arg[0] != '-' && n_files < 2) {
      files[n_files++] = arg;
    } else {
      std::fprintf(stderr, "soiq compare: unexpected argument '%s'\n%s\n", arg.c_str(), kUsage);
      return 2;
    }
  }
  if (n_files != 2) {
    std::fprintf(stderr, "soiq compare: needs two masks\n%s\n", kUsage);
    return 2;
  }
  const Status s = compare_files(files[0], files[1], labels[0], labels[1]);
  if (!s.ok()) {
    std::fprintf(stderr, "soiq compare: %s\n", s.message().c_str());
    return exit_code(s);
  }
  return 0;
}

}  // namespace soiq::cli
