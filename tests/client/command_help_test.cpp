#include "client/cli/command_help.h"

#include <gtest/gtest.h>

#include <string>

#include "client/cli/bash_completion.h"
#include "client/cli/command_table.h"
#include "client/cli/man_page.h"

namespace soiq::cli {
namespace {

bool contains(const std::string& text, std::string_view part) { return text.find(part) != std::string::npos; }

// The help with its wrapped lines joined, so a phrase is found wherever a line broke.
std::string unwrapped(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n') {
      out += text[i];
      continue;
    }
    out += ' ';
    while (i + 1 < text.size() && text[i + 1] == ' ') ++i;
  }
  return out;
}

TEST(CommandHelp, EachCommandShowsSynopsisOptionsWithDefaultsExamplesAndExitCodes) {
  for (const CommandSpec& c : command_table()) {
    const std::string help = unwrapped(command_help(c));
    EXPECT_TRUE(help.starts_with("usage: soiq " + std::string(c.synopsis.front()))) << help;
    for (const OptionSpec& o : c.options) {
      EXPECT_TRUE(contains(command_help(c), "\n  " + std::string(o.name))) << c.name << ": " << o.name;
      if (!o.default_value.empty()) {
        EXPECT_TRUE(contains(help, "(default: " + std::string(o.default_value) + ")")) << c.name << ": " << o.name;
      }
    }
    for (const std::string_view e : c.examples) EXPECT_TRUE(contains(help, e)) << c.name;
    EXPECT_TRUE(contains(help, "Exit codes: 0 ok")) << c.name;
    EXPECT_TRUE(contains(help, "-h, --help")) << c.name;
  }
}

TEST(CommandHelp, QueryHelpNamesWhereAndItsDefaults) {
  const std::string help = *help_topic("query");
  EXPECT_TRUE(contains(help, "--where 'FEATURE OP NUMBER'")) << help;
  EXPECT_TRUE(contains(help, "--format table|json|csv")) << help;
  EXPECT_TRUE(contains(help, "(default: table)")) << help;
  EXPECT_TRUE(contains(help, "--server")) << help;
}

TEST(CommandHelp, OverviewListsEveryCommandTheConnectionOptionsAndTheExitCodes) {
  const std::string overview = overview_help();
  for (const CommandSpec& c : command_table()) {
    if (!c.hidden) {
      EXPECT_TRUE(contains(overview, "soiq " + std::string(c.synopsis.front()))) << c.name;
    }
  }
  for (const OptionSpec& o : global_options()) EXPECT_TRUE(contains(overview, o.name)) << o.name;
  EXPECT_TRUE(contains(overview, "8 partial query answer"));
  EXPECT_TRUE(contains(overview, "id:N"));
  EXPECT_TRUE(contains(overview, "asym(FEATURE)"));
}

TEST(CommandHelp, PacsAloneIsTheHelpOfEverySubcommand) {
  const std::string help = *help_topic("pacs");
  for (const char* verb : {"echo", "find", "pull", "push"}) {
    EXPECT_TRUE(contains(help, "usage: soiq pacs " + std::string(verb))) << verb;
  }
}

TEST(CommandHelp, AnUnknownTopicIsRefusedWithTheClosestCommand) {
  const Result<std::string> help = help_topic("qeury");
  ASSERT_FALSE(help.ok());
  EXPECT_EQ(help.status().code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(help.status().message(), "unknown command 'qeury'; did you mean 'query'?"))
      << help.status().message();
}

TEST(CommandHelp, WrapKeepsLinesWithinTheWidth) {
  const std::string text = wrap("aaa bbb ccc ddd", 2, 10);
  EXPECT_EQ(text, "  aaa bbb\n  ccc ddd\n");
}

TEST(BashCompletion, NamesEveryCommandOptionAndSomeFeatures) {
  const std::string script = bash_completion_script();
  EXPECT_TRUE(contains(script, "complete -F _soiq soiq"));
  for (const CommandSpec& c : command_table()) {
    for (const std::string& o : option_words(c)) EXPECT_TRUE(contains(script, o)) << o;
  }
  EXPECT_TRUE(contains(script, "pacs_find)"));
  EXPECT_TRUE(contains(script, "sphericity"));
  EXPECT_TRUE(contains(script, "values=\"table json csv\""));
}

TEST(ManPage, HasATitleAndEveryCommand) {
  const std::string page = soiq_man_page();
  EXPECT_TRUE(page.starts_with(".TH SOIQ 1"));
  for (const CommandSpec& c : command_table()) {
    EXPECT_TRUE(contains(page, ".SS \"soiq " + roff_escape(c.name) + "\"")) << c.name;
  }
}

TEST(ManPage, EscapesWhatRoffWouldRead) {
  EXPECT_EQ(roff_escape("--where"), "\\-\\-where");
  EXPECT_EQ(roff_escape(".x\n'y a\\b"), "\\&.x\n\\&'y a\\eb");
}

}  // namespace
}  // namespace soiq::cli
