#include "client/cli/remote_options.h"

#include <algorithm>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/quiet.h"

namespace soiq::cli {

Result<client::ClientOptions> take_remote_options(int& argc, char** argv) {
  client::ClientOptions options;
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i], value;
    bool has_value = false;
    const size_t eq = arg.find('=');
    if (arg.starts_with("--") && eq != std::string::npos) {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
      has_value = true;
    }
    if (arg == "--quiet" || arg == "-q") {
      if (has_value) return invalid_argument(arg + " takes no value");
      set_quiet(true);
      continue;
    }
    if (arg != "--server" && arg != "--token-file" && arg != "--tls-ca" && arg != "--timeout") {
      argv[out++] = argv[i];
      continue;
    }
    if (!has_value) {
      if (i + 1 >= argc) return invalid_argument(arg + " needs a value");
      value = argv[++i];
    }
    if (value.empty()) return invalid_argument(arg + " needs a value");
    if (arg == "--server") {
      options.address = value;
    } else if (arg == "--token-file") {
      options.token_file = value;
    } else if (arg == "--tls-ca") {
      options.tls_ca_file = value;
    } else {
      SOIQ_ASSIGN_OR_RETURN(const double seconds, parse_number(value, "--timeout"));
      if (!(seconds > 0) || seconds > 1e7) return invalid_argument("--timeout must be a number of seconds > 0");
      options.deadline = options.stream_deadline = std::chrono::milliseconds(int64_t(seconds * 1000));
    }
  }
  argc = out;
  argv[argc] = nullptr;
  return options;
}

Result<client::Client> connect(const client::ClientOptions& options) { return client::Client::connect(options); }

bool is_structure_id(const std::string& text) {
  return !text.empty() && text.size() <= 18 &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

Result<int64_t> parse_structure_id(const std::string& text) {
  const std::string digits = text.starts_with(kStructureIdPrefix) ? text.substr(kStructureIdPrefix.size()) : text;
  if (!is_structure_id(digits) || std::stoll(digits) <= 0) {
    return invalid_argument("a structure id is a whole number > 0, got '" + text + "'");
  }
  return int64_t(std::stoll(digits));
}

std::string first_operand(int argc, char** argv, const std::vector<std::string>& value_options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() > 1 && arg[0] == '-') {
      if (std::find(value_options.begin(), value_options.end(), arg) != value_options.end()) ++i;
      continue;
    }
    return arg;
  }
  return "";
}

}  // namespace soiq::cli
