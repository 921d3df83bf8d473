// Running an external program (see external_process.h).
#include "gram/external_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace acomms::gram {

ProcessResult run_process(const std::string& executable, const std::vector<std::string>& args,
                          const std::string& directory, std::chrono::duration<double> timeout,
                          const CancelToken& cancel) {
  ProcessResult result;
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    result.end = ProcessResult::End::kNotStarted;
    result.output = std::string("pipe: ") + std::strerror(errno);
    return result;
  }
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(executable.c_str()));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  const pid_t pid = ::fork();
  if (pid == 0) {
    // The child: only async-signal-safe calls until exec.
    ::setpgid(0, 0);
    int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, 0);
    ::dup2(pipe_fds[1], 1);
    ::dup2(pipe_fds[1], 2);
    if (::chdir(directory.c_str()) != 0) ::_exit(126);
    ::execv(executable.c_str(), argv.data());
    const char* why = "cannot execute the engine program\n";
    (void)!::write(2, why, std::strlen(why));
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  if (pid < 0) {
    ::close(pipe_fds[0]);
    result.end = ProcessResult::End::kNotStarted;
    result.output = std::string("fork: ") + std::strerror(errno);
    return result;
  }
  ::setpgid(pid, pid);  // also from here: whichever runs first

  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(timeout);
  bool open = true;
  char buffer[4096];
  while (open) {
    pollfd p{pipe_fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, 50);
    if (ready > 0) {
      const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
      if (n > 0) {
        result.output.append(buffer, static_cast<std::size_t>(n));
        if (result.output.size() > 2 * kOutputTail) result.output.erase(0, result.output.size() - kOutputTail);
      } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
        open = false;  // every writer closed: the program (and its children) ended
      }
    }
    const bool cancelled = cancel.cancelled();
    const bool late = std::chrono::steady_clock::now() >= deadline;
    if (cancelled || late) {
      ::kill(-pid, SIGKILL);
      result.end = cancelled ? ProcessResult::End::kCancelled : ProcessResult::End::kTimedOut;
      break;
    }
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (result.output.size() > kOutputTail) result.output.erase(0, result.output.size() - kOutputTail);
  if (result.end == ProcessResult::End::kExited) {
    if (WIFSIGNALED(status)) {
      result.end = ProcessResult::End::kSignalled;
      result.code = WTERMSIG(status);
    } else {
      result.code = WEXITSTATUS(status);
    }
  }
  return result;
}

}  // namespace acomms::gram
