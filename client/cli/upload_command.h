#pragma once
// `soiq upload MESH --patient ID --study UID --name NAME [--laterality L|R] [--sex M|F|O]
//  [--birth-date YYYYMMDD] [--study-date YYYYMMDD] [--modality MR] [--description D] [--ras]
//  [--robust] [-q]`: stores a surface model on soiqd. Prints
//  "structure ID: NAME L of patient P, study S; T triangles; new surface|surface already stored
//  (deduplicated); DEFECTS", or only the id with -q.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_upload_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
