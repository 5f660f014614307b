#include "client/cli/man_page.h"

#include <cstdio>

#include "client/cli/command_help.h"
#include "client/cli/command_table.h"
#include "client/cli/exit_code.h"

namespace soiq::cli {

namespace {

std::string option_item(const OptionSpec& o) {
  std::string head = "\\fB" + roff_escape(o.name) + "\\fR";
  if (!o.alias.empty()) head += ", \\fB" + roff_escape(o.alias) + "\\fR";
  if (!o.value.empty()) head += " \\fI" + roff_escape(o.value) + "\\fR";
  std::string meaning(o.meaning);
  if (!o.default_value.empty()) meaning += " (default: " + std::string(o.default_value) + ")";
  return ".TP\n" + head + "\n" + roff_escape(meaning) + "\n";
}

std::string command_section(const CommandSpec& c) {
  std::string out = ".SS \"soiq " + roff_escape(c.name) + "\"\n.nf\n";
  for (const std::string_view line : c.synopsis) {
    out += (line.starts_with(' ') ? "     " : "soiq ") + roff_escape(line) + "\n";
  }
  out += ".fi\n.PP\n" + roff_escape(c.description) + "\n";
  if (!c.options.empty()) out += ".RS\n";
  for (const OptionSpec& o : c.options) out += option_item(o);
  if (!c.options.empty()) out += ".RE\n";
  if (!c.examples.empty()) out += ".PP\nExamples:\n.RS\n.nf\n";
  for (const std::string_view e : c.examples) out += roff_escape(e) + "\n";
  if (!c.examples.empty()) out += ".fi\n.RE\n";
  return out;
}

}  // namespace

std::string roff_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '\\') {
      out += "\\e";
    } else if (c == '-') {
      out += "\\-";
    } else if ((c == '.' || c == '\'') && (out.empty() || out.back() == '\n')) {
      out += "\\&";
      out += c;
    } else {
      out += c;
    }
  }
  return out;
}

std::string soiq_man_page() {
  std::string out =
      ".TH SOIQ 1 \"\" \"soiq\" \"User Commands\"\n"
      ".SH NAME\nsoiq \\- query medical images by the content of their structures of interest\n"
      ".SH SYNOPSIS\n.B soiq\n.I COMMAND\n[\\fIOPTION\\fR]... [\\fIARGUMENT\\fR]...\n"
      ".SH DESCRIPTION\n"
      "The offline commands (mesh, convert, features, compare on files) run here; the others talk to "
      "\\fBsoiqd\\fR(8). \\fBsoiq help\\fR \\fICOMMAND\\fR, \\fBsoiq\\fR \\fICOMMAND\\fR \\fB\\-\\-help\\fR and "
      "\\fB\\-h\\fR print a command's help.\n"
      ".SH COMMANDS\n";
  for (const CommandSpec& c : command_table()) out += command_section(c);
  out += ".SH GLOBAL OPTIONS\nBefore or after the command name; the connection's apply to remote commands:\n";
  for (const OptionSpec& o : global_options()) out += option_item(o);
  out += ".SH EXIT STATUS\n" + roff_escape(exit_code_text()) + "\n";
  out +=
      ".SH ENVIRONMENT\n.TP\n.B SOIQ_SERVER\nsoiqd's address when \\fB\\-\\-server\\fR is not given.\n"
      ".TP\n.B SOIQ_MEMORY_BUDGET\nthe memory an offline conversion may use.\n"
      ".SH SEE ALSO\n\\fBsoiqd\\fR(8)\n";
  return out;
}

int run_man_command(int argc, char**, const client::ClientOptions&) {
  if (argc > 1) {
    const Status s = invalid_argument("takes no arguments");
    std::fprintf(stderr, "soiq man: %s\n", s.message().c_str());
    return exit_code(s);
  }
  std::fputs(soiq_man_page().c_str(), stdout);
  return 0;
}

}  // namespace soiq::cli
