// The rows of `soiq query`, `info`, `health` and `demo-load` in the command table.
#include "client/cli/command_table.h"
#include "client/cli/demo_load_command.h"
#include "client/cli/health_command.h"
#include "client/cli/info_command.h"
#include "client/cli/query_command.h"
#include "proto/text/query_options.h"

namespace soiq::cli {
namespace {

// The query's options are the one query table's (proto/text/query_options.h), spelled with dashes,
// and --format and --plot, which only the command line has (the rows' output).
const std::vector<std::string>& dashed_query_names() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const proto_text::QueryOption& o : proto_text::query_options()) names.push_back("--" + std::string(o.name));
    return names;
  }();
  return kNames;
}

std::vector<OptionSpec> query_option_specs() {
  std::vector<OptionSpec> specs;
  const auto options = proto_text::query_options();
  for (size_t i = 0; i < options.size(); ++i) {
    const proto_text::QueryOption& o = options[i];
    specs.push_back({dashed_query_names()[i], o.value, o.default_value, o.meaning});
  }
  specs.push_back({"--format", "table|json|csv", "table", "output format"});
  specs.push_back({"--plot", "FILE.png|.svg", "",
                   "also draw the rows: a histogram of the first --select feature, a scatter of the first two"});
  return specs;
}

// "query [--patient GLOB] [--sex M|F|O] ..." in lines of at most 100 characters.
std::vector<std::string_view> query_synopsis() {
  static const std::vector<std::string> kLines = [] {
    std::vector<std::string> lines = {"query"};
    for (const OptionSpec& o : query_option_specs()) {
      std::string word = "[" + std::string(o.name) + (o.value.empty() ? "" : " " + std::string(o.value)) + "]";
      if (o.name == "--where" || o.name == "--select") word += "...";
      if (lines.back().size() + 1 + word.size() > 100) lines.push_back("     ");
      lines.back() += " " + word;
    }
    return lines;
  }();
  return {kLines.begin(), kLines.end()};
}

}  // namespace

std::vector<CommandSpec> query_commands() {
  return {
      {"query",
       CommandGroup::kRemote,
       query_synopsis(),
       "the two-stage query: records, then features (computed on demand)",
       "Stage 1 filters the records, stage 2 the features (computed on demand). FEATURE is NAME, "
       "NAME[REGION], NAME[REGION,IMAGE], NAME[,IMAGE] or asym(FEATURE), REGION is inside, shell:R or core:R "
       "(mm), IMAGE a modality or series uid (PET means PT); OP is < <= > >= == !=. Rows on stdout; a "
       "progress bar (on a terminal) and a summary line on stderr; Ctrl-C cancels. The same options are "
       "GET /soiq/v1/query's arguments without their dashes.",
       query_option_specs(),
       {"soiq query --name 'amygdala*' --where 'voxel_volume_mm3>1500' --select sphericity",
        "soiq query --where 'mean[shell:5,PT]>2.5' --order-by 'mean[inside,PT]' --desc --limit 10"},
       run_query_command,
       false,
       "stage 1 filters the records, stage 2 the features (computed on demand); FEATURE is NAME, "
       "NAME[REGION], NAME[REGION,IMAGE], NAME[,IMAGE] or asym(FEATURE), REGION is inside, shell:R or core:R "
       "(mm), IMAGE a modality or series uid; OP is < <= > >= == !=. e.g. --where 'voxel_volume_mm3>50000' "
       "--where 'mean[shell:5,PT]>2.5' --order-by 'mean[inside,PT]' --desc; rows on stdout; a progress bar "
       "(on a terminal) and a summary line on stderr; Ctrl-C cancels"},
      {"info",
       CommandGroup::kRemote,
       {"info [--format text|json] [--features]"},
       "soiqd's version, limits and record counts",
       "Prints soiqd's version, limits and record counts; with --features, the features it computes.",
       {{"--format", "text|json", "text", "output format"},
        {"--features", "", "", "also list the features soiqd computes"}},
       {"soiq info", "soiq info --features --format json"},
       run_info_command},
      {"health",
       CommandGroup::kRemote,
       {"health"},
       "asks soiqd's standard health service (grpc.health.v1): SERVING (exit 0) or not (exit 6)",
       "Asks soiqd's standard gRPC health service; exits 0 when it is SERVING, 6 when it is not or cannot "
       "be reached.",
       {},
       {"soiq health --server 127.0.0.1:50051"},
       run_health_command},
      {"demo-load",
       CommandGroup::kRemote,
       {"demo-load [--patients N] [--seed S]"},
       "loads a synthetic cohort (default 20 patients: MR image, hippocampus/amygdala/caudate L and R)",
       "Uploads a synthetic cohort: per patient an MR image and hippocampus, amygdala and caudate, left and "
       "right. The same seed gives the same cohort.",
       {{"--patients", "N", "20", "how many patients (1 to 1000)"}, {"--seed", "S", "1", "the random seed"}},
       {"soiq demo-load", "soiq demo-load --patients 100 --seed 7"},
       run_demo_load_command},
  };
}

}  // namespace soiq::cli
