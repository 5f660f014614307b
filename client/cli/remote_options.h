#pragma once
// The options every command shares — --server HOST:PORT, --token-file F, --tls-ca F,
// --timeout SECONDS (also as --name=value), and --quiet (-q, quiet.h) — taken out of the command
// line wherever they stand (before or after the command name), and the connection they describe.
// $SOIQ_SERVER gives the server when --server is not given; the default is 127.0.0.1:50051.

#include <string>
#include <string_view>
#include <vector>

#include "client/soiq_client.h"
#include "core/base/status.h"

namespace soiq::cli {

// Removes the global options from argv (argc shrinks; argv[0] stays) and returns them as client
// options. INVALID_ARGUMENT for a missing value or a timeout that is not a number of seconds > 0.
Result<client::ClientOptions> take_remote_options(int& argc, char** argv);

// The client of `options`; errors as client::Client::connect.
Result<client::Client> connect(const client::ClientOptions& options);

// A structure id as the command line gives it: all digits, > 0, optionally written `id:N` (which
// `soiq convert` and `soiq features` need when a file N exists too; see structure_operand.h).
inline constexpr std::string_view kStructureIdPrefix = "id:";
bool is_structure_id(const std::string& text);
Result<int64_t> parse_structure_id(const std::string& text);

// The first argument after argv[0] that is neither an option nor the value of one of
// `value_options`; "" when there is none. Decides whether convert/features run remotely.
std::string first_operand(int argc, char** argv, const std::vector<std::string>& value_options);

}  // namespace soiq::cli
