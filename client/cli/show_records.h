#pragma once
// How the records of soiqd read on the command line: one "key: value" block per record for
// `soiq show` and `soiq info`, and the columns of `soiq ls` (row_printer.h).

#include <string>
#include <vector>

#include "client/cli/row_printer.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::cli {

// "64x64x48 voxels of 2x2x2 mm"; "no geometry" when dims are missing.
std::string geometry_text(const soiq::v1::ImageGeometry& g);
// ", slices unevenly spaced" and ", tilted N degrees" (gantry tilt) where they apply, else "".
std::string geometry_notes(const soiq::v1::ImageGeometry& g);

void print_patient(const soiq::v1::Patient& p);
void print_study(const soiq::v1::Study& s);
void print_structure(const soiq::v1::Structure& s);
void print_server_info(const soiq::v1::ServerInfo& info);

// The proto's JSON form (field names as in the .proto), one object on one line.
std::string record_json(const google::protobuf::Message& message);

std::vector<std::string> patient_columns();
std::vector<Cell> patient_cells(const soiq::v1::Patient& p);
std::vector<std::string> study_columns();
std::vector<Cell> study_cells(const soiq::v1::Study& s);
std::vector<std::string> structure_columns();
std::vector<Cell> structure_cells(const soiq::v1::Structure& s);

}  // namespace soiq::cli
