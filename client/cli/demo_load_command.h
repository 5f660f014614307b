#pragma once
// `soiq demo-load [--patients N] [--seed S]`: fills soiqd with the demo configuration
// (demo_cohort_config) of client/cohort/synthetic_cohort.h (default 20 patients, seed 1): per patient an MR image
// (upload-image) and six structures (hippocampus, amygdala, caudate; L and R) as meshes (upload).
// Prints one line per patient, then a total and a few queries to try. Re-running it adds the
// structures again (a structure is new on every upload; the surfaces are deduplicated).

#include "client/soiq_client.h"

namespace soiq::cli {

int run_demo_load_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
