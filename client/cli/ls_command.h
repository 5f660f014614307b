#pragma once
// `soiq ls [patients|studies|structures] [--patient ID|GLOB] [--study UID] [--name GLOB]
//  [--laterality L|R] [--sex M|F|O] [--format table|json|csv] [--all | --page-size N]`:
// lists the records on soiqd (default: patients). Filters: patients by --patient (a GLOB) and
// --sex; studies by --patient (an id); structures by --patient, --study, --name (GLOB, any case)
// and --laterality. One page (100, or N) unless --all; when more remain, a note on stderr says so.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_ls_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
