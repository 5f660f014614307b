// The rows of `soiq query`, `info`, `health` and `demo-load` in the command table.
#include "client/cli/command_table.h"
#include "client/cli/demo_load_command.h"
#include "client/cli/health_command.h"
#include "client/cli/info_command.h"
#include "client/cli/query_command.h"

namespace soiq::cli {

std::vector<CommandSpec> query_commands() {
  return {
      {"query",
       CommandGroup::kRemote,
       {"query [--patient GLOB] [--sex M|F|O] [--min-age Y] [--max-age Y] [--birth-date-from D] [--birth-date-to D]",
        "      [--study-date-from D] [--study-date-to D] [--modality M] [--description GLOB] [--name GLOB]",
        "      [--laterality L|R] [--where 'FEATURE OP NUMBER']... [--select FEATURE]...",
        "      [--order-by FEATURE [--desc]] [--limit N] [--spacing S | --series-modality M]",
        "      [--interpolation nearest|linear] [--format table|json|csv]"},
       "the two-stage query: records, then features (computed on demand)",
       "Stage 1 filters the records, stage 2 the features (computed on demand). FEATURE is NAME, "
       "NAME[REGION], NAME[REGION,IMAGE], NAME[,IMAGE] or asym(FEATURE), REGION is inside, shell:R or core:R "
       "(mm), IMAGE a modality or series uid (PET means PT); OP is < <= > >= == !=. Rows on stdout; a "
       "progress bar (on a terminal) and a summary line on stderr; Ctrl-C cancels.",
       {{"--patient", "GLOB", "", "patient ids (glob: * and ?)"},
        {"--sex", "M|F|O", "", "the patient's sex"},
        {"--min-age", "Y", "", "age at the study, in years, at least"},
        {"--max-age", "Y", "", "age at the study, in years, at most"},
        {"--birth-date-from", "D", "", "born on or after (YYYYMMDD)"},
        {"--birth-date-to", "D", "", "born on or before (YYYYMMDD)"},
        {"--study-date-from", "D", "", "studied on or after (YYYYMMDD)"},
        {"--study-date-to", "D", "", "studied on or before (YYYYMMDD)"},
        {"--modality", "M", "", "a modality of the study (PET means PT)"},
        {"--description", "GLOB", "", "the study's description"},
        {"--name", "GLOB", "", "the structure's name"},
        {"--laterality", "L|R", "", "the structure's side"},
        {"--where", "'FEATURE OP NUMBER'", "", "a condition on a feature; repeatable (all must hold)"},
        {"--select", "FEATURE", "", "a feature column to print; repeatable"},
        {"--order-by", "FEATURE", "structure id", "sort the rows by this feature"},
        {"--desc", "", "", "sort descending (with --order-by; ascending without)"},
        {"--limit", "N", "the server's cap", "at most N rows"},
        {"--spacing", "S|SX,SY,SZ", "1", "grid of the features, in mm (not with --series-modality)"},
        {"--margin", "N", "2", "voxels of margin around the structure (with --spacing)"},
        {"--series-modality", "M", "", "compute on the grid of the study's series of modality M"},
        {"--interpolation", "nearest|linear", "nearest", "how images are sampled"},
        {"--format", "table|json|csv", "table", "output format"}},
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
