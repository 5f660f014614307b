#include "client/cli/operand_dispatch.h"

#include <cstdio>
#include <string>
#include <vector>

#include "client/cli/command_table.h"
#include "client/cli/convert_command.h"
#include "client/cli/exit_code.h"
#include "client/cli/features_command.h"
#include "client/cli/remote_convert_command.h"
#include "client/cli/remote_features_command.h"
#include "client/cli/remote_options.h"
#include "client/cli/structure_operand.h"

namespace soiq::cli {

namespace {

// The options of `name` that take a value, from its row: what first_operand must skip.
std::vector<std::string> value_options(const char* name) {
  std::vector<std::string> names;
  for (const OptionSpec& o : find_command(name)->options) {
    if (o.value.empty()) continue;
    names.emplace_back(o.name);
    if (!o.alias.empty()) names.emplace_back(o.alias);
  }
  return names;
}

// Stored or file; -1 when the operand is refused (the message is printed).
int operand_is_stored(const char* name, int argc, char** argv) {
  const Result<OperandKind> kind = structure_operand_kind(first_operand(argc, argv, value_options(name)));
  if (!kind.ok()) {
    std::fprintf(stderr, "soiq %s: %s\n", name, kind.status().message().c_str());
    return -exit_code(kind.status());
  }
  return *kind == OperandKind::kStored ? 1 : 0;
}

}  // namespace

int run_convert_any(int argc, char** argv, const client::ClientOptions& remote) {
  const int stored = operand_is_stored("convert", argc, argv);
  if (stored < 0) return -stored;
  return stored ? run_remote_convert_command(argc, argv, remote) : run_convert_command(argc, argv);
}

int run_features_any(int argc, char** argv, const client::ClientOptions& remote) {
  const int stored = operand_is_stored("features", argc, argv);
  if (stored < 0) return -stored;
  return stored ? run_remote_features_command(argc, argv, remote) : run_features_command(argc, argv);
}

}  // namespace soiq::cli
