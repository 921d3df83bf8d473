#include "link_raw_command.h"

#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

#include "api_client.h"
#include "global_options.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

struct RawOptions {
  size_t lines = 20;
  bool no_follow = false;
  std::string file;
};

constexpr std::chrono::milliseconds kPoll{200};

struct FileId {
  dev_t device = 0;
  ino_t inode = 0;
  bool operator==(const FileId&) const = default;
};

std::optional<FileId> file_id(const std::filesystem::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return std::nullopt;
  return FileId{info.st_dev, info.st_ino};
}

// Prints the whole lines `in` has from its position on; a partial last
// line is left for the next call.
void print_rest(std::ifstream& in) {
  std::string line;
  while (std::getline(in, line)) {
    if (in.eof()) {
      // A line still being written: read it whole next time.
      in.clear();
      in.seekg(-static_cast<std::streamoff>(line.size()), std::ios::cur);
      return;
    }
    std::printf("%s\n", line.c_str());
  }
  in.clear();
  std::fflush(stdout);
}

void run_raw(const GlobalOptions& global, const RawOptions& options) {
  std::filesystem::path path = options.file;
  if (path.empty()) {
    ApiClient client(global);
    v1::Status status = client.call(&v1::Acomms::Stub::GetStatus, v1::GetStatusRequest());
    path = std::filesystem::path(status.data_dir()) / "link-raw.log";
  }
  std::ifstream in(path);
  if (!in) {
    throw UsageError("no raw link log at " + path.string() +
                     " (acommsd writes one for the micromodem driver, in its data dir on this machine)");
  }
  std::deque<std::string> last;
  std::string line;
  while (std::getline(in, line)) {
    last.push_back(line);
    if (last.size() > options.lines) last.pop_front();
  }
  for (const std::string& l : last) std::printf("%s\n", l.c_str());
  std::fflush(stdout);
  if (options.no_follow) return;
  in.clear();
  std::optional<FileId> id = file_id(path);
  for (;;) {
    std::this_thread::sleep_for(kPoll);
    print_rest(in);
    std::optional<FileId> now = file_id(path);
    if (now && now != id) {
      // Rotated: the old file is finished (printed above); start the new one.
      in = std::ifstream(path);
      id = now;
      print_rest(in);
    }
  }
}

}  // namespace

void add_link_raw_command(CLI::App& link, const GlobalOptions& options) {
  static RawOptions raw_options;
  CLI::App* raw = link.add_subcommand("raw", "Follow every line to and from the modem (the raw link log)");
  raw->add_option("-n,--lines", raw_options.lines, "Lines of history to print first (default 20)");
  raw->add_flag("--no-follow", raw_options.no_follow, "Print the history and exit");
  raw->add_option("--file", raw_options.file, "Read this log instead of the daemon's <data_dir>/link-raw.log");
  raw->footer(
      "Each line: UTC time, \"<<\" from the modem or \">>\" to it, the bytes (non-printable ones as \\xHH). "
      "Reads the daemon's data dir, so run it on the daemon's machine.\n\n"
      "Example:\n  acommsctl link raw -n 50");
  raw->callback([&options] { run_raw(options, raw_options); });
}

}  // namespace acomms::cli
