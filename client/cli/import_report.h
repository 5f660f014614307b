#pragma once
// What an import stored, as `soiq import` and `soiq pacs pull` print it: one row per patient,
// study, series and structure on stdout (columns what, id, patient, detail; table, json or csv),
// then each problem and one summary line on stderr.

#include <string>

#include "soiq/v1/soiq.pb.h"

namespace soiq::cli {

void print_import_report(const soiq::v1::ImportDicomResponse& r, const std::string& format);

}  // namespace soiq::cli
