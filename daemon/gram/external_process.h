// Running an external model program with a time limit, stoppable.
//
// Problem: a worker that waits on a program that hangs is lost for good,
// and a program's error text is the only thing that tells its user what to
// fix. Decision: the program runs in its own process group, in a given
// directory, stdin from /dev/null, stdout and stderr into one pipe whose
// last kOutputTail bytes are kept; the caller's thread polls the pipe every
// 50 ms and checks the time limit and the cancel token; on either the whole
// group gets SIGKILL and is reaped, so nothing outlives the run.
// Thread-safe (each call its own process); async-signal-safe after fork.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "gram/cancel_token.h"

namespace acomms::gram {

inline constexpr std::size_t kOutputTail = 8192;

struct ProcessResult {
  enum class End { kExited, kSignalled, kTimedOut, kCancelled, kNotStarted } end = End::kExited;
  int code = 0;        // exit status, or the signal
  std::string output;  // stdout and stderr, the last kOutputTail bytes
};

ProcessResult run_process(const std::string& executable, const std::vector<std::string>& args,
                          const std::string& directory, std::chrono::duration<double> timeout,
                          const CancelToken& cancel);

}  // namespace acomms::gram
