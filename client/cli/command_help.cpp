#include "client/cli/command_help.h"

#include <cstdio>

#include "core/base/did_you_mean.h"

namespace soiq::cli {

namespace {

// "  --select FEATURE" padded to the meaning's column, or the meaning on the next line when the
// name is too long; ends with a newline.
std::string option_line(const OptionSpec& o) {
  std::string head = "  " + std::string(o.name);
  if (!o.alias.empty()) head += ", " + std::string(o.alias);
  if (!o.value.empty()) head += " " + std::string(o.value);
  std::string meaning(o.meaning);
  if (!o.default_value.empty()) meaning += " (default: " + std::string(o.default_value) + ")";
  constexpr size_t kColumn = 30;
  if (head.size() + 2 > kColumn) return head + "\n" + wrap(meaning, kColumn);
  return head + std::string(kColumn - head.size(), ' ') + wrap(meaning, kColumn).substr(kColumn);
}

std::string group_overview(CommandGroup group) {
  std::string out;
  for (const CommandSpec& c : command_table()) {
    if (c.group != group || c.hidden) continue;
    for (const std::string_view line : c.synopsis) {
      out += (line.starts_with(' ') ? "       " : "  soiq ") + std::string(line) + "\n";
    }
    out += wrap(c.summary, 6);
    if (!c.overview_note.empty()) out += wrap(c.overview_note, 6);
  }
  return out;
}

}  // namespace

std::string wrap(std::string_view text, size_t indent, size_t width) {
  std::string out, line;
  size_t from = 0;
  while (from < text.size()) {
    size_t end = text.find(' ', from);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view word = text.substr(from, end - from);
    if (!line.empty() && indent + line.size() + 1 + word.size() > width) {
      out += std::string(indent, ' ') + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + std::string(word);
    from = end + 1;
  }
  if (!line.empty()) out += std::string(indent, ' ') + line + "\n";
  return out;
}

std::string_view exit_code_text() {
  return "Exit codes: 0 ok, 1 other, 2 invalid argument or usage, 3 not found, 4 already exists or failed "
         "precondition, 5 resource exhausted, 6 unavailable, deadline or cancelled, 7 unauthenticated or "
         "permission denied, 8 partial query answer (some candidates skipped; the summary says why), 130 "
         "interrupted by Ctrl-C (the command says what it kept). Errors are one line on stderr.";
}

std::string overview_help() {
  std::string out = "soiq - query medical images by the content of their structures of interest\n\n";
  out += "Offline commands (no server needed):\n" + group_overview(CommandGroup::kOffline) + "\n";
  out += "Remote commands (talk to soiqd):\n" + group_overview(CommandGroup::kRemote) + "\n";
  out += "About soiq itself:\n" + group_overview(CommandGroup::kOther) + "\n";
  out += "Global options, before or after the command name (the connection's apply to remote commands):\n";
  for (const OptionSpec& o : global_options()) out += option_line(o);
  out += "\n" + wrap(exit_code_text(), 0);
  out += "'soiq help COMMAND' or 'soiq COMMAND --help' prints a command's options, defaults and examples.\n";
  return out;
}

std::string command_help(const CommandSpec& c) {
  std::string out;
  for (size_t i = 0; i < c.synopsis.size(); ++i) {
    // A line that starts with a blank continues the one before; any other is another form.
    const char* lead = i == 0 ? "usage: soiq " : c.synopsis[i].starts_with(' ') ? "            " : "       soiq ";
    out += lead + std::string(c.synopsis[i]) + "\n";
  }
  out += "\n" + wrap(c.description, 0) + "\nOptions:\n";
  for (const OptionSpec& o : c.options) out += option_line(o);
  out += option_line({"-h", "", "", "print this help", "--help"});
  out += "\nGlobal options (see 'soiq help'):";
  for (const OptionSpec& o : global_options())
    out += " " + std::string(o.name) + (o.value.empty() ? "" : " " + std::string(o.value));
  out += "\n";
  if (!c.examples.empty()) out += "\nExamples:\n";
  for (const std::string_view e : c.examples) out += "  " + std::string(e) + "\n";
  out += "\n" + wrap(exit_code_text(), 0);
  return out;
}

Result<std::string> help_topic(std::string_view topic) {
  if (const CommandSpec* c = find_command(topic)) return command_help(*c);
  std::string all;
  for (const CommandSpec& c : command_table()) {
    if (c.name.starts_with(std::string(topic) + " ")) all += (all.empty() ? "" : "\n") + command_help(c);
  }
  if (!all.empty()) return all;
  return invalid_argument("unknown command '" + std::string(topic) + "'" + did_you_mean(topic, command_words()) +
                          " (soiq help lists them)");
}

}  // namespace soiq::cli
