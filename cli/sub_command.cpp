#include "sub_command.h"

#include <signal.h>

#include <atomic>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "api_client.h"
#include "global_options.h"
#include "output.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

struct SubOptions {
  std::vector<std::string> types;
  int32_t src = 0;
  CLI::Option* src_option = nullptr;
  std::string resume_file;
};

// `sub --resume FILE`: the seq of the last message printed, kept in FILE so
// that a reader started again (by cron, after a crash) goes on from there.
// Written after the line is flushed, by rename, so FILE always holds one
// whole number: a kill between the two repeats at most that one line, and
// never loses one (a missed command is worse than a repeated line).
class ResumeCursor {
 public:
  explicit ResumeCursor(std::string path) : path_(std::move(path)) {}

  // The seq to resume after: 0 (everything still held) when FILE does not
  // exist yet. Throws CLI::ValidationError naming FILE when it is not a number.
  int64_t load() const {
    std::ifstream in(path_);
    if (!in) return 0;
    int64_t seq = 0;
    if (!(in >> seq) || seq < 0) {
      throw CLI::ValidationError("--resume", path_ + " does not hold a sequence number (0 or more)");
    }
    return seq;
  }

  void save(int64_t seq) const {
    const std::string temporary = path_ + ".tmp";
    {
      std::ofstream out(temporary, std::ios::trunc);
      out << seq << '\n';
      out.flush();
      if (!out) throw std::runtime_error("cannot write " + temporary);
    }
    std::filesystem::rename(temporary, path_);
  }

 private:
  std::string path_;
};

// SIGINT/SIGTERM end a subscription normally (exit 0). They are blocked
// and taken by a watcher thread, because the main thread sits in a
// blocking Read that only cancelling the call can end.
class StopOnSignal {
 public:
  explicit StopOnSignal(grpc::ClientContext& context) {
    sigemptyset(&signals_);
    sigaddset(&signals_, SIGINT);
    sigaddset(&signals_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals_, nullptr);
    watcher_ = std::thread([this, &context] {
      const timespec poll{0, 100'000'000};
      while (!done_) {
        if (sigtimedwait(&signals_, nullptr, &poll) > 0) {
          stopped_ = true;
          context.TryCancel();
          return;
        }
      }
    });
  }
  ~StopOnSignal() {
    done_ = true;
    watcher_.join();
  }
  bool stopped() const { return stopped_; }

 private:
  sigset_t signals_{};
  std::atomic<bool> done_{false};
  std::atomic<bool> stopped_{false};
  std::thread watcher_;
};

std::string line_for(const v1::ReceivedMessage& received) {
  // The message is embedded as an object, not a string, so `jq .message.x` works.
  const std::string& message = received.json().empty() ? std::string("null") : received.json();
  return "{\"type\":" + json_quote(received.type()) + ",\"src\":" + std::to_string(received.src()) +
         ",\"dest\":" + std::to_string(received.dest()) + ",\"receive_time\":" + number_text(received.receive_time()) +
         ",\"message\":" + message + ",\"link\":" + json_with_defaults(received.link()) +
         ",\"seq\":" + std::to_string(received.seq()) + "}";
}

void run_sub(const GlobalOptions& global, const SubOptions& options) {
  // Blocked before the channel exists, so gRPC's own threads inherit the
  // mask and the watcher is the only one to see the signals.
  grpc::ClientContext context;
  StopOnSignal stop(context);
  ApiClient client(global);
  v1::SubscribeRequest request;
  for (const std::string& type : options.types) request.add_types(type);
  if (options.src_option->count() > 0) request.set_src(options.src);
  std::optional<ResumeCursor> cursor;
  if (!options.resume_file.empty()) {
    cursor.emplace(options.resume_file);
    request.set_after(cursor->load());
  }
  std::unique_ptr<grpc::ClientReader<v1::ReceivedMessage>> reader = client.stub().Subscribe(&context, request);
  v1::ReceivedMessage received;
  while (reader->Read(&received)) {
    // A pipe to another program is read line by line as messages arrive.
    std::cout << line_for(received) << std::endl;
    // seq 0: a driver-specific reception (a mini-packet), never stored: no place to resume from.
    if (cursor && received.seq() != 0) cursor->save(received.seq());
  }
  grpc::Status status = reader->Finish();
  if (stop.stopped()) return;
  check(status);
}

}  // namespace

void add_sub_command(CLI::App& app, const GlobalOptions& global) {
  static SubOptions options;
  CLI::App* sub = app.add_subcommand("sub", "Follow messages received from the link, one JSON line each");
  sub->add_option("TYPE", options.types, "Only these types (default: every type)")->type_name("");
  options.src_option = sub->add_option("--src", options.src, "Only messages from this modem id")->type_name("ID");
  sub->add_option("--resume", options.resume_file,
                  "Keep the last message's seq in FILE and start after it: nothing received meanwhile is "
                  "missed (a missing FILE starts from the oldest message the daemon still holds)")
      ->type_name("FILE");
  sub->footer(
      "Each line: type, src, dest, receive_time, message (the decoded fields, as JSON), link (who "
      "transmitted, rate, quality; absent on messages replayed from the store) and seq (this node's "
      "received sequence number). Runs until Ctrl-C (exit 0); exits 1 if the daemon ends the stream "
      "(it is stopping, or this reader fell too far behind and was dropped).\n\n"
      "Examples:\n"
      "  acommsctl sub\n"
      "  acommsctl sub gv.NavigationReport --src 2 | jq .message\n"
      "  acommsctl sub --resume ~/.acomms-sub.cursor >> received.jsonl");
  sub->callback([&global] { run_sub(global, options); });
}

}  // namespace acomms::cli
