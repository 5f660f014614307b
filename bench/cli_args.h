#pragma once
// The command line of one soiq-bench subcommand: positional arguments and `--name value` options
// (`--flag` alone for booleans). Unknown options are an error, so a typo never runs the wrong
// benchmark silently.

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::bench {

struct CliArgs {
  std::vector<std::string> positional;
  std::map<std::string, std::string> options;  // "--runs" -> "5"; a flag maps to ""

  bool has(const std::string& name) const { return options.count(name) != 0; }
  std::string get(const std::string& name, const std::string& fallback) const;
  // INVALID_ARGUMENT when present but not an integer / number.
  Result<int> get_int(const std::string& name, int fallback) const;
  Result<double> get_double(const std::string& name, double fallback) const;
};

// Parses argv[first..argc). `flags` take no value; every other option in `valued` takes one.
Result<CliArgs> parse_cli_args(int argc, char** argv, int first, const std::set<std::string>& valued,
                               const std::set<std::string>& flags);

}  // namespace soiq::bench
