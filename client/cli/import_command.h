#pragma once
// `soiq import PATH... [--format table|json|csv]`: sends DICOM files and folders (recursively) to
// soiqd, which stores their CT, MR and PET series and RT Structure Set ROIs (ImportDicom). Prints one
// row per patient, study, series and structure imported (columns: what, id, patient, detail);
// problems (skipped files, series, ROIs) and a summary line go to stderr, with a progress bar of the
// bytes sent when stderr is a terminal. Exit 0 when something was imported; otherwise the server's
// error (nothing is stored then).

#include "client/soiq_client.h"

namespace soiq::cli {

int run_import_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
