#include "sub_command.h"

#include <signal.h>

#include <atomic>
#include <ctime>
#include <iostream>
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
         ",\"message\":" + message + ",\"link\":" + to_json(received.link()) + "}";
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
  std::unique_ptr<grpc::ClientReader<v1::ReceivedMessage>> reader = client.stub().Subscribe(&context, request);
  v1::ReceivedMessage received;
  while (reader->Read(&received)) {
    // A pipe to another program is read line by line as messages arrive.
    std::cout << line_for(received) << std::endl;
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
  sub->footer(
      "Each line: type, src, dest, receive_time, message (the decoded fields, as JSON) and link (who "
      "transmitted, rate, quality). Runs until Ctrl-C (exit 0); exits 1 if the daemon ends the stream "
      "(it is stopping, or this reader fell too far behind and was dropped).\n\n"
      "Examples:\n"
      "  acommsctl sub\n"
      "  acommsctl sub gv.NavigationReport --src 2 | jq .message");
  sub->callback([&global] { run_sub(global, options); });
}

}  // namespace acomms::cli
