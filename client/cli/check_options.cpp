#include "client/cli/check_options.h"

#include <string>

#include "core/base/did_you_mean.h"

namespace soiq::cli {

namespace {

bool is_option(const std::string& arg) { return arg.size() > 1 && arg[0] == '-'; }

bool is_help(const std::string& arg) { return arg == "-h" || arg == "--help"; }

// Calls `visit` with each argument that stands where an option may; stops at the first false.
template <typename Visit>
void each_option(const CommandSpec& command, int argc, char** argv, int from, Visit&& visit) {
  for (int i = from; i < argc; ++i) {
    const std::string arg = argv[i];
    if (!is_option(arg)) continue;
    const size_t eq = arg.find('=');
    const std::string name = arg.starts_with("--") && eq != std::string::npos ? arg.substr(0, eq) : arg;
    if (!visit(name)) return;
    const OptionSpec* o = find_option(command, name);
    if (o && !o->value.empty() && name == arg) ++i;
  }
}

}  // namespace

Status check_options(const CommandSpec& command, int argc, char** argv, int from) {
  Status status = ok_status();
  each_option(command, argc, argv, from, [&](const std::string& name) {
    if (is_help(name) || find_option(command, name)) return true;
    const std::string listed = command.options.empty() ? " (it takes none)" : "";
    status = invalid_argument("unknown option '" + name + "'" + listed + did_you_mean(name, option_words(command)));
    return false;
  });
  return status;
}

bool asks_for_help(const CommandSpec& command, int argc, char** argv, int from) {
  bool help = false;
  each_option(command, argc, argv, from, [&](const std::string& name) {
    help = help || is_help(name);
    return !help;
  });
  return help;
}

}  // namespace soiq::cli
