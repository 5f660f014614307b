#include "client/cli/remote_convert_command.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/fraction_args.h"
#include "client/cli/grid_args.h"
#include "client/cli/progress_bar.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "client/cli/show_records.h"
#include "core/io/read_image.h"
#include "core/io/write_image.h"

namespace soiq::cli {

namespace {

struct RemoteConvertArgs {
  soiq::v1::ConvertRequest request;
  std::string out;
  FractionArgs fractions;
};

Result<RemoteConvertArgs> parse_remote_convert_args(int argc, char** argv) {
  RemoteConvertArgs a;
  GridArgs grid;
  std::string id;
  for (int i = 1; i < argc; ++i) {
    SOIQ_ASSIGN_OR_RETURN(const bool is_grid, parse_grid_option(argc, argv, i, grid));
    if (is_grid) continue;
    SOIQ_ASSIGN_OR_RETURN(const bool is_fraction, parse_fraction_option(argc, argv, i, a.fractions));
    if (is_fraction) continue;
    const std::string arg = argv[i];
    if (arg == "-o" || arg == "--output") {
      SOIQ_ASSIGN_OR_RETURN(a.out, option_value(argc, argv, i));
    } else if (arg == "--even-odd") {
      a.request.set_fill_rule(soiq::v1::EVEN_ODD);
    } else if (arg == "--robust" || arg == "--ras" || arg == "--reference" || arg == "--threads") {
      return invalid_argument(arg + " applies to a mesh file; a stored structure keeps how it was uploaded" +
                              (arg == "--reference" ? " (use --series UID for a stored image's grid)" : ""));
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else if (id.empty()) {
      id = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  SOIQ_ASSIGN_OR_RETURN(const int64_t structure_id, parse_structure_id(id));
  a.request.set_structure_id(structure_id);
  SOIQ_RETURN_IF_ERROR(check_grid_args(grid));
  if (grid.given || grid.margin_given) *a.request.mutable_grid() = grid.grid;
  if (a.out.empty()) return invalid_argument("missing -o OUT");
  if (!ends_with(a.out, ".nii.gz") && !ends_with(a.out, ".nii") && !ends_with(a.out, ".nrrd") &&
      !ends_with(a.out, ".mha")) {
    return invalid_argument("output '" + a.out + "' has an unknown extension; use .nii.gz, .nii, .nrrd or .mha");
  }
  a.request.set_encoding(soiq::v1::NIFTI_GZ);
  SOIQ_RETURN_IF_ERROR(check_fraction_args(a.fractions));
  if (a.fractions.fractional) {
    a.request.set_oversample(a.fractions.lines_per_voxel());
    a.request.set_fraction_type(a.fractions.float32 ? soiq::v1::FRACTION_FLOAT32 : soiq::v1::FRACTION_UINT8);
  }
  return a;
}

Status convert(const RemoteConvertArgs& a, const client::ClientOptions& remote) {
  SOIQ_RETURN_IF_ERROR(make_output_folder(a.out));
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  // soiqd sends .nii.gz; any other format goes through a temporary file beside the output.
  const bool direct = ends_with(a.out, ".nii.gz");
  const std::string path = direct ? a.out : a.out + ".part.nii.gz";
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) return not_found("cannot write '" + path + "'");
  ProgressBar bar;
  int64_t expected = 0, received = 0;
  client::ConvertHandlers handlers;
  handlers.on_summary = [&](const soiq::v1::ConvertSummary& s) {
    expected = s.nifti_bytes();
    return true;
  };
  handlers.on_nifti = [&](std::string_view bytes) {
    file.write(bytes.data(), std::streamsize(bytes.size()));
    received += int64_t(bytes.size());
    bar.update("receiving", received, std::max(expected, received));
    return bool(file);
  };
  const Result<soiq::v1::ConvertSummary> summary = c.convert(a.request, handlers);
  bar.clear();
  file.close();
  if (!summary.ok() || !file) {
    std::remove(path.c_str());
    if (interrupted()) return interrupted_by_user("no output was written");
    return summary.ok() ? data_loss("error writing '" + path + "' (disk full?)") : summary.status();
  }
  if (!direct) {
    Result<Image> image = read_image(path);
    std::remove(path.c_str());
    if (!image.ok()) return image.status();
    if (a.fractions.fractional) {
      // Fractions keep their values: bytes 0-255 stay bytes, floats stay floats.
      Mask bytes{image->geometry, std::vector<uint8_t>(image->voxels.begin(), image->voxels.end())};
      SOIQ_RETURN_IF_ERROR(a.fractions.float32 ? write_image(*image, a.out) : write_mask(bytes, a.out));
    } else {
      SOIQ_RETURN_IF_ERROR(write_mask(mask_from_image(*image), a.out));
    }
  }
  const soiq::v1::ConvertSummary& s = *summary;
  if (a.fractions.fractional) {
    std::printf(
        "%lld voxels inside or partly (%lld partly), %.3f mm3 by fractions (%dx%d lines per voxel) on %s; %.2f "
        "ms -> %s (%s)\n",
        (long long)s.voxel_count(), (long long)s.partial_voxels(), s.volume_mm3(), s.oversample(), s.oversample(),
        geometry_text(s.geometry()).c_str(), s.milliseconds(), a.out.c_str(),
        a.fractions.float32 ? "float32 0-1" : "uint8 0-255");
    return ok_status();
  }
  std::printf("%lld voxels inside, %.3f mm3 on %s; %s; %.2f ms -> %s\n", (long long)s.voxel_count(), s.volume_mm3(),
              geometry_text(s.geometry()).c_str(), s.defects().c_str(), s.milliseconds(), a.out.c_str());
  return ok_status();
}

}  // namespace

int run_remote_convert_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command(
      "convert", parse_remote_convert_args(argc, argv), remote,
      [](const RemoteConvertArgs& a, const client::ClientOptions& options) { return convert(a, options); });
}

}  // namespace soiq::cli
