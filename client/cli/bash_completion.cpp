#include "client/cli/bash_completion.h"

#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "client/cli/command_table.h"
#include "client/cli/exit_code.h"
#include "core/features/feature_catalogue.h"

namespace soiq::cli {

namespace {

std::string join(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

// The words of a value placeholder with a closed set of them ("table|json|csv", "L|R",
// "inside|shell:R|core:R"); empty for an open one ("ID|GLOB", "S|SX,SY,SZ", "N").
std::vector<std::string> value_words(std::string_view placeholder) {
  std::vector<std::string> words;
  size_t from = 0;
  while (from <= placeholder.size()) {
    size_t bar = placeholder.find('|', from);
    if (bar == std::string_view::npos) bar = placeholder.size();
    std::string w(placeholder.substr(from, bar - from));
    if (w.ends_with(":R")) w.pop_back();  // shell:R -> shell: (the reader types the radius)
    const bool one_capital = w.size() == 1 && std::isupper(static_cast<unsigned char>(w[0]));
    bool lower = !w.empty();
    for (const char c : w) lower = lower && (std::islower(static_cast<unsigned char>(c)) || c == '-' || c == ':');
    if (!one_capital && !lower) return {};
    words.push_back(w);
    from = bar + 1;
  }
  return words.size() > 1 ? words : std::vector<std::string>{};
}

std::vector<std::string> feature_words() {
  std::vector<std::string> names = shape_feature_names();
  for (const std::string& n : intensity_feature_names()) {
    if (!find_shape_feature(n)) names.push_back(n);
  }
  for (const std::string& n : weighted_feature_names()) names.push_back(n);
  return names;
}

// The regions a feature expression names inside its brackets ("shell:" and "core:" take a radius).
std::vector<std::string> region_words() { return {"inside", "shell:", "core:"}; }

// The case arm `key) opts="..."; values=...` of one command ("pacs find" is keyed pacs_find).
std::string command_arm(const CommandSpec& c) {
  std::string key(c.name);
  for (char& ch : key) ch = ch == ' ' ? '_' : ch;
  std::vector<std::string> options, takes;
  std::string values;
  for (const OptionSpec& o : c.options) {
    options.emplace_back(o.name);
    if (!o.alias.empty()) options.emplace_back(o.alias);
    if (o.value.empty()) continue;
    takes.emplace_back(o.name);
    const std::vector<std::string> words = value_words(o.value);
    if (!words.empty()) values += "      " + std::string(o.name) + ") values=\"" + join(words) + "\" ;;\n";
  }
  options.emplace_back("--help");
  std::string arm = "    " + key + ")\n      opts=\"" + join(options) + "\"\n";
  if (!takes.empty()) arm += "      takes=\"" + join(takes) + "\"\n";
  if (!values.empty()) arm += "      case \"$prev\" in\n" + values + "      esac\n";
  return arm + "      ;;\n";
}

}  // namespace

std::string bash_completion_script() {
  std::vector<std::string> commands, pacs, connection;
  for (const CommandSpec& c : command_table()) {
    if (c.name.starts_with("pacs ")) pacs.emplace_back(c.name.substr(5));
  }
  commands = command_words();
  for (const OptionSpec& o : global_options()) connection.emplace_back(o.name);
  std::string arms;
  for (const CommandSpec& c : command_table()) arms += command_arm(c);
  return "# bash completion for soiq; made by `soiq completion bash` from its command table.\n"
         "_soiq() {\n"
         "  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}\n"
         "  local cmd='' i\n"
         "  for ((i = 1; i < COMP_CWORD; i++)); do\n"
         "    case ${COMP_WORDS[i]} in\n"
         "      --server | --token-file | --tls-ca | --timeout) ((i++)) ;;\n"
         "      -*) ;;\n"
         "      *) if [[ -z $cmd ]]; then cmd=${COMP_WORDS[i]}; elif [[ $cmd == pacs ]]; then "
         "cmd=pacs_${COMP_WORDS[i]};"
         " break; else break; fi ;;\n"
         "    esac\n"
         "  done\n"
         "  case $prev in\n"
         "    --server | --token-file | --tls-ca | --timeout) COMPREPLY=($(compgen -f -- \"$cur\")); return ;;\n"
         "  esac\n"
         "  if [[ -z $cmd ]]; then\n"
         "    COMPREPLY=($(compgen -W \"" +
         join(commands) + " " + join(connection) +
         "\" -- \"$cur\"))\n"
         "    return\n"
         "  fi\n"
         "  if [[ $cmd == pacs ]]; then\n"
         "    COMPREPLY=($(compgen -W \"" +
         join(pacs) +
         "\" -- \"$cur\"))\n"
         "    return\n"
         "  fi\n"
         "  local opts='' takes='' values=''\n"
         "  case $cmd in\n" +
         arms +
         "  esac\n"
         "  local features=\"" +
         join(feature_words()) +
         "\"\n"
         "  case $prev in\n"
         "    --select | --order-by | --where)\n"
         // Inside an expression: after NAME[ the regions; after asym( or an opening quote, the names.
         "      if [[ $cur == *\\[* && $cur != *\\]* ]]; then\n"
         "        local head=${cur%\\[*} tail=${cur##*\\[}\n"
         "        [[ $tail == *,* ]] || COMPREPLY=($(compgen -P \"$head[\" -W \"" +
         join(region_words()) +
         "\" -- \"$tail\"))\n"
         "        return\n"
         "      fi\n"
         "      local word=${cur##*[^a-z_0-9]}\n"
         "      COMPREPLY=($(compgen -P \"${cur%\"$word\"}\" -W \"$features\" -- \"$word\"))\n"
         "      return ;;\n"
         "    --features)\n"
         "      local head=${cur%,*} tail=${cur##*,}\n"
         "      [[ $cur == *,* ]] && head=\"$head,\" || head=''\n"
         "      COMPREPLY=($(compgen -P \"$head\" -W \"$features\" -- \"$tail\"))\n"
         "      return ;;\n"
         "  esac\n"
         "  if [[ -n $values ]]; then COMPREPLY=($(compgen -W \"$values\" -- \"$cur\")); return; fi\n"
         "  if [[ \" $takes \" == *\" $prev \"* ]]; then COMPREPLY=($(compgen -f -- \"$cur\")); return; fi\n"
         "  if [[ $cur == -* ]]; then\n"
         "    COMPREPLY=($(compgen -W \"$opts " +
         join(connection) +
         "\" -- \"$cur\"))\n"
         "  else\n"
         "    COMPREPLY=($(compgen -f -- \"$cur\"))\n"
         "  fi\n"
         "}\n"
         "complete -F _soiq soiq\n";
}

int run_completion_command(int argc, char** argv, const client::ClientOptions&) {
  if (argc != 2 || std::string(argv[1]) != "bash") {
    const Status s = invalid_argument("give the shell: soiq completion bash (the one supported)");
    std::fprintf(stderr, "soiq completion: %s\n", s.message().c_str());
    return exit_code(s);
  }
  std::fputs(bash_completion_script().c_str(), stdout);
  return 0;
}

}  // namespace soiq::cli
