#pragma once
// Runs a real binary for integration tests: arguments, extra environment,
// stdout and stderr captured to files, and signals.

#include <sys/types.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace acomms::testing {

class ChildProcess {
 public:
  // Starts `program` with `args`; stdout/stderr go to `log_prefix`.out/.err,
  // stdin comes from `stdin_path` (/dev/null when empty).
  ChildProcess(const std::string& program, const std::vector<std::string>& args,
               const std::string& log_prefix, const std::map<std::string, std::string>& env = {},
               const std::string& stdin_path = "");
  ~ChildProcess();  // SIGKILLs a child still running

  pid_t pid() const { return pid_; }
  void signal(int signal_number);
  // Exit code, or nullopt if it did not exit within `timeout` (or died by a
  // signal: then exit_signal() says which).
  std::optional<int> wait(std::chrono::milliseconds timeout);
  bool running();
  int exit_signal() const { return exit_signal_; }
  std::string stdout_text() const;
  std::string stderr_text() const;

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int exit_code_ = -1;
  int exit_signal_ = 0;
  std::string log_prefix_;
};

struct RunResult {
  int exit_code;
  std::string out;
  std::string err;
};

// Runs to completion (or kills after `timeout`).
RunResult run(const std::string& program, const std::vector<std::string>& args,
              const std::string& log_prefix,
              std::chrono::milliseconds timeout = std::chrono::seconds(30));

// The same, with `input` written to the program's stdin.
RunResult run_with_input(const std::string& program, const std::vector<std::string>& args,
                         const std::string& log_prefix, const std::string& input);

// A program's output split at '\n', without the newlines (no empty last line
// for output that ends with one).
std::vector<std::string> lines_of(const std::string& text);

}  // namespace acomms::testing
