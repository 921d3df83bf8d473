#pragma once
// `acommsctl completion bash`: a bash completion script, generated from the
// command tree itself so that it cannot fall behind the commands. A copy is
// kept in cli/completion/acommsctl.bash (for packaging); a test checks that
// the two are equal.

#include <CLI/CLI.hpp>

#include <string>

namespace acomms::cli {

// Add last: the script covers every command added before the call runs.
void add_completion_command(CLI::App& app);

// The script for `app`'s command tree.
std::string bash_completion_script(CLI::App& app);

}  // namespace acomms::cli
