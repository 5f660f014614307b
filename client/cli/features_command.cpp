#include "client/cli/features_command.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "client/cli/cli_args.h"
#include "client/cli/exit_code.h"
#include "client/cli/feature_list_output.h"
#include "client/cli/feature_report_output.h"
#include "client/cli/mesh_on_grid.h"
#include "client/cli/structure_operand.h"
#include "core/features/structure_features.h"
#include "core/io/read_image.h"

namespace soiq::cli {

namespace {

struct FeaturesArgs {
  std::string input;
  int label = -1;
  MeshGridOptions grid;
  std::vector<std::pair<std::string, std::string>> images;  // name, path
  std::vector<RegionSpec> regions;
  std::vector<std::string> names;
  std::string format = "table";
  Interpolation interpolation = Interpolation::kNearest;
  bool ibsi = false;
  bool list = false;  // --list: print the feature catalogue instead
};

// "PET=pet.nii.gz" or "pet.nii.gz" (named after the file, without directories and extensions).
std::pair<std::string, std::string> named_image(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq != std::string::npos && eq > 0) return {text.substr(0, eq), text.substr(eq + 1)};
  std::string name = text.substr(text.find_last_of('/') == std::string::npos ? 0 : text.find_last_of('/') + 1);
  name = name.substr(0, name.find('.'));
  return {name, text};
}

Result<FeaturesArgs> parse_features_args(int argc, char** argv) {
  FeaturesArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* flag) -> Result<std::string> {
      if (i + 1 >= argc) return invalid_argument(std::string(flag) + " needs a value");
      return std::string(argv[++i]);
    };
    SOIQ_ASSIGN_OR_RETURN(const bool shared, parse_mesh_grid_option(argc, argv, i, a.grid));
    if (shared) continue;
    if (arg == "--label") {
      SOIQ_ASSIGN_OR_RETURN(std::string text, value("--label"));
      SOIQ_ASSIGN_OR_RETURN(a.label, parse_int(text, "--label", 0, 1 << 30));
    } else if (arg == "--image") {
      SOIQ_ASSIGN_OR_RETURN(std::string text, value("--image"));
      a.images.push_back(named_image(text));
    } else if (arg == "--region") {
      SOIQ_ASSIGN_OR_RETURN(std::string text, value("--region"));
      SOIQ_ASSIGN_OR_RETURN(RegionSpec r, parse_region(text));
      a.regions.push_back(r);
    } else if (arg == "--features") {
      SOIQ_ASSIGN_OR_RETURN(std::string text, value("--features"));
      size_t from = 0;
      for (size_t comma; (comma = text.find(',', from)) != std::string::npos; from = comma + 1) {
        if (comma > from) a.names.push_back(text.substr(from, comma - from));
      }
      if (from < text.size()) a.names.push_back(text.substr(from));
    } else if (arg == "--format") {
      SOIQ_ASSIGN_OR_RETURN(a.format, value("--format"));
      if (a.format != "table" && a.format != "json" && a.format != "csv" && a.format != "markdown") {
        return invalid_argument("--format must be table, json or csv (or markdown with --list)");
      }
    } else if (arg == "--list") {
      a.list = true;
    } else if (arg == "--interpolation") {
      SOIQ_ASSIGN_OR_RETURN(std::string text, value("--interpolation"));
      if (text != "nearest" && text != "linear") return invalid_argument("--interpolation must be nearest or linear");
      a.interpolation = text == "linear" ? Interpolation::kLinear : Interpolation::kNearest;
    } else if (arg == "--ibsi") {
      a.ibsi = true;
    } else if (!arg.empty() && arg[0] == '-') {
      SOIQ_RETURN_IF_ERROR(refuse_stored_only_option(arg, "features"));
      return invalid_argument("unknown option '" + arg + "'");
    } else if (a.input.empty()) {
      a.input = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (a.list) {
    if (!a.input.empty()) return invalid_argument("--list takes no INPUT");
    if (a.format == "json") return invalid_argument("--list prints table, csv or markdown");
    return a;
  }
  if (a.format == "markdown") return invalid_argument("--format markdown is for --list");
  if (a.input.empty()) return invalid_argument("missing INPUT (a surface model or a mask)");
  SOIQ_RETURN_IF_ERROR(check_mesh_grid_options(a.grid));
  if (a.regions.empty()) a.regions.push_back(RegionSpec{});
  return a;
}

// The structure: a surface model converted by the 1D method, or a mask read as it is.
Result<StructureInput> load_structure(const FeaturesArgs& a) {
  StructureInput s;
  if (!is_mesh_path(a.input)) {
    SOIQ_ASSIGN_OR_RETURN(Image image, read_image(a.input));
    s.volume = from_mask(mask_from_image(image, a.label));
    return s;
  }
  SOIQ_ASSIGN_OR_RETURN(MeshOnGrid m, convert_mesh_file(a.input, a.grid));
  s.volume = std::move(m.voxels.volume);
  s.surface = std::make_shared<const TriangleMesh>(std::move(m.mesh));
  return s;
}

Status features(const FeaturesArgs& a) {
  if (a.list) {
    print_feature_list(catalogue_rows(), a.format);
    return ok_status();
  }
  SOIQ_ASSIGN_OR_RETURN(StructureInput structure, load_structure(a));
  std::vector<std::unique_ptr<Image>> images;
  FeatureRequest request;
  for (const auto& [name, path] : a.images) {
    SOIQ_ASSIGN_OR_RETURN(Image image, read_image(path));
    images.push_back(std::make_unique<Image>(std::move(image)));
    request.images.push_back({name, images.back().get()});
  }
  request.names = a.names;
  request.regions = a.regions;
  request.interpolation = a.interpolation;
  request.covariance = a.ibsi ? CovarianceDivisor::kNMinus1 : CovarianceDivisor::kN;
  request.threads = a.grid.threads;
  request.fill_rule = a.grid.even_odd ? FillRule::kEvenOdd : FillRule::kNonZero;
  SOIQ_ASSIGN_OR_RETURN(FeatureReport report, structure_features(structure, request));
  print_feature_report(report, a.format);
  return ok_status();
}

}  // namespace

int run_features_command(int argc, char** argv) {
  return run_command("features", parse_features_args(argc, argv), features);
}

}  // namespace soiq::cli
