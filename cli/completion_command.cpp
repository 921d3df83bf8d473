#include "completion_command.h"

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "events_command.h"

namespace acomms::cli {
namespace {

// One command of the tree, as the script needs it.
struct CommandWords {
  std::string path;                  // "", "defs", "defs load", ...
  std::vector<std::string> words;    // subcommands, then options
  std::vector<const CLI::Option*> value_options;
  std::string positional;            // type name of its positional, e.g. "TYPE"
  bool has_subcommands = false;
};

std::vector<CLI::App*> named_subcommands(CLI::App& app) {
  return app.get_subcommands([](CLI::App* sub) { return !sub->get_name().empty(); });
}

void add_options(const CLI::App& app, CommandWords* command) {
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_group().empty()) continue;  // hidden
    if (option->get_positional() && option->get_lnames().empty() && option->get_snames().empty()) {
      if (command->positional.empty()) command->positional = option->get_name();
      continue;
    }
    for (const std::string& name : option->get_lnames()) command->words.push_back("--" + name);
    for (const std::string& name : option->get_snames()) command->words.push_back("-" + name);
    if (option->get_expected_min() > 0) command->value_options.push_back(option);
  }
}

// Depth first, in the order the commands were added (the order --help shows).
void collect(CLI::App& app, const std::string& path, const CommandWords* parent, std::vector<CommandWords>* out) {
  CommandWords command;
  command.path = path;
  std::vector<CLI::App*> subs = named_subcommands(app);
  command.has_subcommands = !subs.empty();
  for (CLI::App* sub : subs) command.words.push_back(sub->get_name());
  add_options(app, &command);
  // Global options may follow the subcommand (fallthrough); a command's
  // own option of the same name (send --json) shadows the global one.
  if (parent != nullptr) {
    for (const std::string& word : parent->words) {
      const bool own = std::find(command.words.begin(), command.words.end(), word) != command.words.end();
      if (word.rfind("-", 0) == 0 && !own && word != "--help" && word != "-h" && word != "--version") {
        command.words.push_back(word);
      }
    }
    for (const CLI::Option* option : parent->value_options) command.value_options.push_back(option);
  }
  out->push_back(command);
  for (CLI::App* sub : subs) collect(*sub, path.empty() ? sub->get_name() : path + " " + sub->get_name(), &command, out);
}

std::string join(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& w : words) text += (text.empty() ? "" : " ") + w;
  return text;
}

// The compgen call that completes a value of this type name.
std::string reply_for(std::string type_name) {
  // CLI11 appends validators ("KIND:{queued,...}"); the name comes first.
  type_name = type_name.substr(0, type_name.find(':'));
  if (type_name == "TYPE") return "COMPREPLY=($(compgen -W \"$(_acommsctl_types)\" -- \"$cur\"))";
  if (type_name == "KIND") return "COMPREPLY=($(compgen -W \"" + join(event_kinds()) + "\" -- \"$cur\"))";
  if (type_name == "FILE" || type_name == "SOCKET") return "COMPREPLY=($(compgen -f -- \"$cur\"))";
  if (type_name == "DIR") return "COMPREPLY=($(compgen -d -- \"$cur\"))";
  return "COMPREPLY=()";
}

std::string option_pattern(const CLI::Option* option) {
  std::vector<std::string> names;
  for (const std::string& name : option->get_snames()) names.push_back("-" + name);
  for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  std::string pattern;
  for (const std::string& n : names) pattern += (pattern.empty() ? "" : "|") + n;
  return pattern;
}

std::string case_for(const CommandWords& command) {
  std::string text = "    \"" + command.path + "\")\n";
  if (!command.value_options.empty()) {
    // Values nothing can suggest (numbers, text) still must not be
    // completed as subcommands: one branch gives them an empty reply.
    std::string no_reply;
    text += "      case \"$prev\" in\n";
    for (const CLI::Option* option : command.value_options) {
      const std::string reply = reply_for(option->get_type_name());
      if (reply == "COMPREPLY=()") {
        no_reply += (no_reply.empty() ? "" : "|") + option_pattern(option);
      } else {
        text += "        " + option_pattern(option) + ") " + reply + "; return ;;\n";
      }
    }
    if (!no_reply.empty()) text += "        " + no_reply + ") COMPREPLY=(); return ;;\n";
    text += "      esac\n";
  }
  const std::string words = "COMPREPLY=($(compgen -W \"" + join(command.words) + "\" -- \"$cur\"))";
  if (command.has_subcommands || command.positional.empty() || reply_for(command.positional) == "COMPREPLY=()") {
    text += "      " + words + " ;;\n";
  } else {
    text += "      if [[ \"$cur\" == -* ]]; then " + words + "; else " + reply_for(command.positional) + "; fi ;;\n";
  }
  return text;
}

const char* const kHeader = R"(# bash completion for acommsctl.
# Generated by `acommsctl completion bash`: do not edit. Install it as
# /usr/share/bash-completion/completions/acommsctl, or `source <(acommsctl completion bash)`.

# Type names from the daemon (the one --socket names, if given), quietly.
_acommsctl_types() {
  local socket="" i
  for ((i = 1; i < COMP_CWORD; i++)); do
    case "${COMP_WORDS[i]}" in
      -s|--socket) socket="${COMP_WORDS[i+1]}" ;;
    esac
  done
  acommsctl ${socket:+--socket "$socket"} --timeout 1 defs list --names 2>/dev/null
}

_acommsctl() {
  local cur="${COMP_WORDS[COMP_CWORD]}" prev="${COMP_WORDS[COMP_CWORD-1]}"
  local path="" word i
  # The command so far: the words that name subcommands, in order.
  for ((i = 1; i < COMP_CWORD; i++)); do
    word="${COMP_WORDS[i]}"
    case "${path:+$path }$word" in
)";

const char* const kFooter = R"(  esac
}
complete -F _acommsctl acommsctl
)";

}  // namespace

std::string bash_completion_script(CLI::App& app) {
  std::vector<CommandWords> commands;
  collect(app, "", nullptr, &commands);
  std::string script = kHeader;
  std::string paths;
  for (const CommandWords& command : commands) {
    if (!command.path.empty()) paths += (paths.empty() ? "" : "|") + ("\"" + command.path + "\"");
  }
  script += "      " + paths + ") path=\"${path:+$path }$word\" ;;\n";
  script += "    esac\n  done\n  case \"$path\" in\n";
  for (const CommandWords& command : commands) script += case_for(command);
  return script + kFooter;
}

void add_completion_command(CLI::App& app) {
  CLI::App* completion = app.add_subcommand(
      "completion", "Print a shell completion script: commands, options, and type names from the daemon");
  static std::string shell;
  completion->add_option("SHELL", shell, "Only bash for now")->required()->type_name("")->check(CLI::IsMember({"bash"}));
  completion->footer(
      "Examples:\n"
      "  source <(acommsctl completion bash)\n"
      "  acommsctl completion bash | sudo tee /usr/share/bash-completion/completions/acommsctl");
  completion->callback([&app] { std::cout << bash_completion_script(app); });
}

}  // namespace acomms::cli
