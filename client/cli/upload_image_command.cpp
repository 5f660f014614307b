#include "client/cli/upload_image_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/progress_bar.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "client/cli/show_records.h"

namespace soiq::cli {

namespace {

struct UploadImageArgs {
  std::string image;
  soiq::v1::UploadImageHeader header;
};

Result<UploadImageArgs> parse_upload_image_args(int argc, char** argv) {
  UploadImageArgs a;
  soiq::v1::Study& study = *a.header.mutable_study();
  for (int i = 1; i < argc; ++i) {
    SOIQ_ASSIGN_OR_RETURN(const bool record, parse_record_option(argc, argv, i, *a.header.mutable_patient(), study));
    if (record) continue;
    const std::string arg = argv[i];
    if (arg == "--series") {
      SOIQ_ASSIGN_OR_RETURN(*a.header.mutable_series_uid(), option_value(argc, argv, i));
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else if (a.image.empty()) {
      a.image = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "' (one IMAGE per upload)");
    }
  }
  if (a.image.empty()) return invalid_argument("missing IMAGE");
  if (client::format_from_path(a.image).empty() || is_mesh_path(a.image)) {
    return invalid_argument("'" + a.image + "' is not an image; use .nii, .nii.gz, .nrrd or .mha");
  }
  SOIQ_RETURN_IF_ERROR(check_record(a.header.patient(), study));
  if (a.header.series_uid().empty()) return invalid_argument("missing --series UID");
  // --modality names the series' modality here; the study keeps it too when it has none.
  if (study.modality().empty()) return invalid_argument("missing --modality (e.g. MR, CT, PT)");
  a.header.set_modality(study.modality());
  return a;
}

Status upload_image(const UploadImageArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  ProgressBar bar;
  const Result<soiq::v1::UploadImageResponse> uploaded =
      c.upload_image(a.header, a.image, [&](int64_t done, int64_t total) { bar.update("sending", done, total); });
  bar.clear();
  if (!uploaded.ok() && interrupted()) return interrupted_by_user("nothing was stored");
  if (!uploaded.ok()) return in_upload_option_words(uploaded.status());
  const soiq::v1::UploadImageResponse& r = *uploaded;
  std::printf("series %s: %s, %s; %s\n", r.series().series_uid().c_str(), r.series().modality().c_str(),
              geometry_text(r.series().geometry()).c_str(), r.replaced() ? "replaced" : "new");
  return ok_status();
}

}  // namespace

int run_upload_image_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command(
      "upload-image", parse_upload_image_args(argc, argv), remote,
      [](const UploadImageArgs& a, const client::ClientOptions& options) { return upload_image(a, options); });
}

}  // namespace soiq::cli
