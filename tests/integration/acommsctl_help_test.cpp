// What a user reads in `acommsctl ... --help`: every command, found by
// walking the Subcommands lists from the top, ends with examples of its
// own. CLI11 copies a parent's footer into the subcommands made after it,
// which once put the top-level workflow (`defs load ... nav.proto ...`)
// under commands it has nothing to do with, such as `gram env update`.
//
// And the examples are right: each invocation in them names the command it
// is shown under (or, on a group, one of its commands), and those of the
// commands that talk to the daemon, run against a socket where no daemon
// listens, get as far as the daemon (they fail at reaching it, or for want
// of the input the example reads, never with a usage error). The
// offline commands' examples (dccl, sim, gram ssp|tl|arrivals, completion, fleet)
// would run for real, so they are not run here.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;

const std::string kAcommsctl = ACOMMSCTL_BINARY;

// CLI11's own words when it refuses the arguments.
constexpr const char* kParseFailure = "for more information";

std::vector<std::string> words_of(const std::string& path) {
  std::vector<std::string> words;
  std::istringstream in(path);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

class AcommsctlHelpTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("acomms-ctl-help-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    // Every command, breadth first from the top ("" is acommsctl itself).
    std::vector<std::string> pending{""};
    while (!pending.empty()) {
      const std::string path = pending.front();
      pending.erase(pending.begin());
      const std::string help = help_of(path);
      help_[path] = help;
      for (const std::string& name : subcommands_in(help)) pending.push_back(path.empty() ? name : path + " " + name);
    }
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string help_of(const std::string& path) {
    std::vector<std::string> args = words_of(path);
    args.push_back("--help");
    RunResult result = run(kAcommsctl, args, (dir_ / "help").string());
    EXPECT_EQ(result.exit_code, 0) << path << ": " << result.err;
    return result.out;
  }

  // The names listed under "Subcommands:".
  static std::vector<std::string> subcommands_in(const std::string& help) {
    std::vector<std::string> names;
    bool listing = false;
    for (const std::string& line : lines_of(help)) {
      if (line == "Subcommands:") {
        listing = true;
      } else if (listing) {
        if (line.size() < 3 || line.rfind("  ", 0) != 0 || line[2] == ' ') break;
        names.push_back(line.substr(2, line.find(' ', 2) - 2));
      }
    }
    return names;
  }

  // The indented lines under the last "Example..." heading: the footer's
  // examples (the footer comes last in CLI11's help).
  static std::vector<std::string> examples_in(const std::string& help) {
    std::vector<std::string> examples;
    bool heading = false;
    for (const std::string& line : lines_of(help)) {
      if (line.rfind("Example", 0) == 0) {
        heading = true;
        examples.clear();
      } else if (heading && line.rfind("  ", 0) == 0) {
        examples.push_back(line.substr(2));
      }
    }
    return examples;
  }

  // The acommsctl invocations in an example line, each split into its
  // arguments as a shell would (quotes; stops at a pipe, &&, a redirection,
  // the end of a process substitution or a comment).
  static std::vector<std::vector<std::string>> invocations_in(const std::string& example) {
    std::vector<std::vector<std::string>> found;
    for (std::size_t at = example.find("acommsctl "); at != std::string::npos;
         at = example.find("acommsctl ", at + 1)) {
      if (at > 0 && example[at - 1] != ' ' && example[at - 1] != '(') continue;
      std::vector<std::string> args;
      std::string word;
      bool in_word = false;
      char quote = 0;
      std::size_t i = at + std::string("acommsctl ").size();
      for (; i < example.size(); ++i) {
        const char c = example[i];
        if (quote) {
          if (c == quote) quote = 0;
          else if (c == '\\' && quote == '"' && i + 1 < example.size()) word += example[++i];
          else word += c;
        } else if (c == '\'' || c == '"') {
          quote = c;
          in_word = true;
        } else if (c == ' ') {
          if (in_word) args.push_back(word);
          word.clear();
          in_word = false;
        } else if (std::string("|&><;)").find(c) != std::string::npos || (c == '#' && !in_word)) {
          break;
        } else {
          word += c;
          in_word = true;
        }
      }
      if (in_word) args.push_back(word);
      found.push_back(args);
    }
    return found;
  }

  // The command an invocation runs: its longest leading run of words (after
  // the global options) that is a command's path.
  static std::string command_of(const std::vector<std::string>& args) {
    static const std::set<std::string> kGlobalWithValue = {"-s", "--socket", "--timeout", "--ca", "--cert", "--key"};
    std::vector<std::string> words;
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (kGlobalWithValue.contains(args[i]) && words.empty()) {
        ++i;
      } else if (args[i].rfind("-", 0) == 0) {
        if (!words.empty()) break;
      } else {
        words.push_back(args[i]);
      }
    }
    std::string path, longest;
    for (const std::string& word : words) {
      path += (path.empty() ? "" : " ") + word;
      if (help_.contains(path)) longest = path;
    }
    return longest;
  }

  static bool is_offline(const std::string& command) {
    for (const char* offline : {"dccl", "sim", "gram ssp", "gram tl", "gram arrivals", "completion", "fleet"}) {
      const std::string prefix(offline);
      if (command == prefix || command.rfind(prefix + " ", 0) == 0) return true;
    }
    return false;
  }

  static bool names(const std::string& command, const std::string& path) {
    return command == path || command.rfind(path + " ", 0) == 0;
  }

  static inline fs::path dir_;
  static inline std::map<std::string, std::string> help_;
};

TEST_F(AcommsctlHelpTest, TheWalkFindsEveryCommandGroup) {
  for (const char* path : {"status", "defs load", "queue cancel", "link cycle", "link ping", "gram env update",
                           "gram depth", "sim depth-adaptation", "dccl analyze", "completion", "fleet check"})
    EXPECT_TRUE(help_.contains(path)) << path;
  EXPECT_GE(help_.size(), 40u);
}

TEST_F(AcommsctlHelpTest, EveryCommandEndsWithExamplesOfItself) {
  for (const auto& [path, help] : help_) {
    if (path.empty()) continue;
    const std::vector<std::string> examples = examples_in(help);
    ASSERT_FALSE(examples.empty()) << "`acommsctl " << path << " --help` has no examples:\n" << help;
    bool shows_itself = false;
    for (const std::string& example : examples)
      for (const auto& args : invocations_in(example)) shows_itself = shows_itself || names(command_of(args), path);
    EXPECT_TRUE(shows_itself) << "no example of `acommsctl " << path << "` runs it:\n" << help;
  }
}

TEST_F(AcommsctlHelpTest, NoTwoCommandsShowTheSameExamples) {
  std::map<std::vector<std::string>, std::string> shown_by;
  for (const auto& [path, help] : help_) {
    const std::vector<std::string> examples = examples_in(help);
    auto [it, first] = shown_by.emplace(examples, path);
    EXPECT_TRUE(first) << "`acommsctl " << path << " --help` shows the examples of `acommsctl " << it->second
                       << "`";
  }
}

TEST_F(AcommsctlHelpTest, TheDaemonCommandsExamplesGetPastTheArgumentParser) {
  const std::string no_daemon = (dir_ / "no-daemon.sock").string();
  int run_count = 0;
  for (const auto& [path, help] : help_) {
    for (const std::string& example : examples_in(help)) {
      for (std::vector<std::string> args : invocations_in(example)) {
        const std::string command = command_of(args);
        ASSERT_FALSE(command.empty()) << "`" << example << "` (under " << path << ") runs no command";
        if (is_offline(command)) continue;
        for (std::size_t i = 0; i + 1 < args.size(); ++i)
          if (args[i] == "-s" || args[i] == "--socket") args[i + 1] = no_daemon;
        ChildProcess ctl(kAcommsctl, args, (dir_ / ("run" + std::to_string(++run_count))).string(),
                         {{"ACOMMSD_SOCKET", no_daemon}});
        const std::optional<int> code = ctl.wait(std::chrono::seconds(30));
        ASSERT_TRUE(code.has_value()) << "`" << example << "` did not finish";
        const std::string err = ctl.stderr_text();
        EXPECT_EQ(err.find(kParseFailure), std::string::npos)
            << "`" << example << "` (under " << path << ") is refused by the parser: " << err;
        EXPECT_EQ(err.rfind("acommsctl: ", 0), 0u) << "`" << example << "`: " << err;
        // 1: it went for the daemon. Otherwise only for want of the input
        // the example reads (a file here, or lines on stdin).
        const bool wants_input = err.find("cannot read") != std::string::npos || err.find("no input") != std::string::npos;
        EXPECT_TRUE(*code == 1 || wants_input)
            << "`" << example << "` (under " << path << ") stops before the daemon, exit " << *code << ": " << err;
      }
    }
  }
  EXPECT_GT(run_count, 30);
}

}  // namespace
}  // namespace acomms::testing
