#include "client/cli/command_table.h"

#include <algorithm>

namespace soiq::cli {

std::span<const CommandSpec> command_table() {
  static const std::vector<CommandSpec> table = [] {
    std::vector<CommandSpec> all;
    for (auto group : {offline_commands, record_commands, pacs_commands, query_commands, other_commands}) {
      for (CommandSpec& c : group()) all.push_back(std::move(c));
    }
    return all;
  }();
  return table;
}

const CommandSpec* find_command(std::string_view name) {
  for (const CommandSpec& c : command_table())
    if (c.name == name) return &c;
  return nullptr;
}

const OptionSpec* find_option(const CommandSpec& command, std::string_view name) {
  for (const OptionSpec& o : command.options)
    if (o.name == name || (!o.alias.empty() && o.alias == name)) return &o;
  return nullptr;
}

std::vector<std::string> command_words() {
  std::vector<std::string> words;
  for (const CommandSpec& c : command_table()) {
    const std::string word(c.name.substr(0, c.name.find(' ')));
    if (std::find(words.begin(), words.end(), word) == words.end()) words.push_back(word);
  }
  return words;
}

std::vector<std::string> option_words(const CommandSpec& command) {
  std::vector<std::string> words;
  for (const OptionSpec& o : command.options) {
    words.emplace_back(o.name);
    if (!o.alias.empty()) words.emplace_back(o.alias);
  }
  return words;
}

std::span<const OptionSpec> global_options() {
  static const OptionSpec options[] = {
      {"--server", "ADDRESS", "$SOIQ_SERVER, else 127.0.0.1:50051",
       "soiqd's address: HOST[:PORT], [IPV6]:PORT, http://HOST:PORT (plaintext), https://HOST:PORT (TLS), "
       "unix:PATH (default port 50051)"},
      {"--token-file", "F", "", "send the bearer token in F (authorization: Bearer ...)"},
      {"--tls-ca", "F", "", "use TLS and verify soiqd's certificate against the PEM roots in F"},
      {"--timeout", "SECONDS", "30 s; 600 s for uploads, conversions, queries", "deadline of each call"},
      {"--quiet", "", "",
       "no progress bars, notes or summaries on stderr (errors and skipped candidates still show); "
       "'soiq upload' prints only the new id",
       "-q"},
  };
  return options;
}

}  // namespace soiq::cli
