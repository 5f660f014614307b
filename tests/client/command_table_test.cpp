// The command table against the parsers it describes: every option a row lists is spelled in its
// parser's source, every option the command's own parser file spells is listed, and query's parser
// accepts each option its row lists. Together with check_options (nothing unlisted reaches a
// parser), help and parser cannot disagree.
#include "client/cli/command_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "client/cli/query_args.h"
#include "proto/text/query_options.h"

namespace soiq::cli {
namespace {

// The parser sources of each command. Each file but the shared helpers (kShared, which spell
// options of several commands) is held to list every option it spells.
const std::map<std::string, std::vector<std::string>> kParserSources = {
    {"mesh", {"mesh_command.cpp"}},
    {"convert",
     {"convert_command.cpp", "remote_convert_command.cpp", "mesh_on_grid.cpp", "grid_args.cpp", "fraction_args.cpp"}},
    {"features", {"features_command.cpp", "remote_features_command.cpp", "mesh_on_grid.cpp", "grid_args.cpp"}},
    {"compare", {"compare_command.cpp"}},
    {"upload", {"upload_command.cpp", "record_args.cpp"}},
    {"upload-image", {"upload_image_command.cpp", "record_args.cpp"}},
    {"import", {"import_command.cpp"}},
    {"export-seg", {"export_seg_command.cpp", "fraction_args.cpp"}},
    {"export-rtstruct", {"export_rt_struct_command.cpp"}},
    {"render", {"render_command.cpp"}},
    {"pacs echo", {"pacs_command.cpp"}},
    {"pacs find", {"pacs_command.cpp"}},
    {"pacs pull", {"pacs_command.cpp"}},
    {"pacs push", {"pacs_command.cpp"}},
    {"ls", {"ls_command.cpp"}},
    {"show", {"show_command.cpp"}},
    {"rm", {"rm_command.cpp"}},
    {"download", {"download_command.cpp"}},
    {"query", {"query_args.cpp"}},  // and the query table: QueryRowIsTheQueryTable
    {"info", {"info_command.cpp"}},
    {"health", {"health_command.cpp"}},
    {"demo-load", {"demo_load_command.cpp"}},
    {"help", {"help_command.cpp"}},
    {"completion", {"bash_completion.cpp"}},
    {"man", {"man_page.cpp"}},
};

const std::set<std::string> kShared = {"mesh_on_grid.cpp", "grid_args.cpp", "record_args.cpp"};

std::string read_source(const std::string& name) {
  std::ifstream in(std::string(SOIQ_SOURCE_DIR) + "/client/cli/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every "--option" or "-o" string literal of a source: a quote, one or two dashes, a lower-case
// letter, then lower-case letters, digits and dashes up to the closing quote. (A hand scan: GCC
// 12's <regex> trips -Wmaybe-uninitialized in the sanitizer build.)
std::set<std::string> option_literals(const std::string& source) {
  const auto word_char = [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-'; };
  std::set<std::string> found;
  for (size_t q = source.find('"'); q != std::string::npos; q = source.find('"', q + 1)) {
    size_t i = q + 1;
    const size_t dashes = source.compare(i, 2, "--") == 0 ? 2 : source.compare(i, 1, "-") == 0 ? 1 : 0;
    if (dashes == 0 || i + dashes >= source.size() || !(source[i + dashes] >= 'a' && source[i + dashes] <= 'z'))
      continue;
    i += dashes;
    while (i < source.size() && word_char(source[i])) ++i;
    if (i < source.size() && source[i] == '"') found.insert(source.substr(q + 1, i - q - 1));
  }
  return found;
}

std::set<std::string> listed_options(const CommandSpec& c) {
  std::set<std::string> names;
  for (const std::string& w : option_words(c)) names.insert(w);
  return names;
}

TEST(CommandTable, EveryCommandHasItsParserSourcesNamedHere) {
  for (const CommandSpec& c : command_table()) {
    EXPECT_TRUE(kParserSources.contains(std::string(c.name))) << c.name;
    EXPECT_NE(c.run, nullptr) << c.name;
    EXPECT_FALSE(c.synopsis.empty()) << c.name;
    EXPECT_FALSE(c.summary.empty()) << c.name;
    EXPECT_FALSE(c.examples.empty()) << c.name;
  }
  EXPECT_EQ(kParserSources.size(), command_table().size());
}

TEST(CommandTable, EveryListedOptionIsSpelledInItsParser) {
  for (const CommandSpec& c : command_table()) {
    std::set<std::string> spelled;
    for (const std::string& file : kParserSources.at(std::string(c.name))) {
      const std::string source = read_source(file);
      ASSERT_FALSE(source.empty()) << file;
      spelled.merge(option_literals(source));
    }
    for (const std::string& o : listed_options(c)) {
      // The query's options come from the query table itself (QueryRowIsTheQueryTable).
      if (c.name == "query" && o.starts_with("--") && proto_text::find_query_option(o.substr(2)) != nullptr) continue;
      EXPECT_TRUE(spelled.contains(o)) << c.name << " lists " << o;
    }
  }
}

TEST(CommandTable, EveryOptionAParserSpellsIsListed) {
  std::map<std::string, std::set<std::string>> listed_by_file;  // pacs_command.cpp serves four rows
  for (const CommandSpec& c : command_table()) {
    for (const std::string& file : kParserSources.at(std::string(c.name))) {
      if (!kShared.contains(file)) listed_by_file[file].merge(listed_options(c));
    }
  }
  for (const auto& [file, listed] : listed_by_file) {
    for (const std::string& o : option_literals(read_source(file))) {
      if (o == "-h" || o == "--help") continue;  // every command's, held by check_options
      EXPECT_TRUE(listed.contains(o)) << file << " accepts " << o << ", which its row does not list";
    }
  }
}

TEST(CommandTable, QueryRowIsTheQueryTable) {
  std::vector<std::string> want;
  for (const proto_text::QueryOption& o : proto_text::query_options()) want.push_back("--" + std::string(o.name));
  want.push_back("--format");
  want.push_back("--plot");
  std::vector<std::string> listed;
  for (const OptionSpec& o : find_command("query")->options) listed.push_back(std::string(o.name));
  EXPECT_EQ(listed, want);
}

TEST(CommandTable, QueryParserAcceptsEveryListedOption) {
  for (const OptionSpec& o : find_command("query")->options) {
    std::vector<std::string> args = {"query", std::string(o.name)};
    if (!o.value.empty()) args.push_back("1");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const Result<QueryArgs> r = parse_query_args(int(args.size()), argv.data());
    if (!r.ok()) {
      EXPECT_EQ(r.status().message().find("unknown option"), std::string::npos) << r.status().message();
    }
  }
}

TEST(CommandTable, NamesAndOptionsAreUnique) {
  std::set<std::string_view> names;
  for (const CommandSpec& c : command_table()) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    const std::vector<std::string> words = option_words(c);
    EXPECT_EQ(std::set<std::string>(words.begin(), words.end()).size(), words.size()) << c.name;
  }
}

TEST(CommandTable, FindsCommandsAndOptionsByEitherSpelling) {
  ASSERT_NE(find_command("pacs find"), nullptr);
  EXPECT_EQ(find_command("pacs"), nullptr);
  EXPECT_EQ(find_option(*find_command("download"), "--output"), find_option(*find_command("download"), "-o"));
  const std::vector<std::string> words = command_words();
  EXPECT_EQ(std::count(words.begin(), words.end(), "pacs"), 1);
}

}  // namespace
}  // namespace soiq::cli
