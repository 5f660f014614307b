#include "bench/cli_args.h"

#include <cstdlib>

namespace soiq::bench {

std::string CliArgs::get(const std::string& name, const std::string& fallback) const {
  const auto it = options.find(name);
  return it == options.end() ? fallback : it->second;
}

Result<int> CliArgs::get_int(const std::string& name, int fallback) const {
  const auto it = options.find(name);
  if (it == options.end()) return fallback;
  char* end = nullptr;
  const long v = std::strtol(it->second.c_str(), &end, 10);
  if (it->second.empty() || *end != '\0') return invalid_argument(name + " needs an integer, got '" + it->second + "'");
  return int(v);
}

Result<double> CliArgs::get_double(const std::string& name, double fallback) const {
  const auto it = options.find(name);
  if (it == options.end()) return fallback;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0') return invalid_argument(name + " needs a number, got '" + it->second + "'");
  return v;
}

Result<CliArgs> parse_cli_args(int argc, char** argv, int first, const std::set<std::string>& valued,
                               const std::set<std::string>& flags) {
  CliArgs out;
  for (int a = first; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("--", 0) != 0 && arg != "-o") {
      out.positional.push_back(arg);
    } else if (flags.count(arg)) {
      out.options[arg] = "";
    } else if (valued.count(arg)) {
      if (a + 1 >= argc) return invalid_argument(arg + " needs a value");
      out.options[arg] = argv[++a];
    } else {
      return invalid_argument("unknown option '" + arg + "'");
    }
  }
  return out;
}

}  // namespace soiq::bench
