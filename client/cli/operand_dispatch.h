#pragma once
// `soiq convert` and `soiq features` run offline on a file or on soiqd for a stored structure id
// (structure_operand.h decides by the operand). These run the right one; the operand is the first
// argument that is neither an option nor the value of one (the values are those the command table
// lists). Exit status as the command run; 2 when the operand is ambiguous.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_convert_any(int argc, char** argv, const client::ClientOptions& remote);
int run_features_any(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
