// The process queue_crash_test kills: submits from several threads as fast
// as it can, through the same path as the daemon's Submit, or receives as
// fast as it can, acknowledging the way the link does; it reports on stdout
// only what has been confirmed. See queue_crash_protocol.h.
//
//   queue_crash_child <data dir> <threads> <proto file>
//   queue_crash_child <data dir> receive <proto file>

#include <google/protobuf/text_format.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/clock.h"
#include "core/event_loop.h"
#include "queue/durable_receipts.h"
#include "queue/queue_manager.h"
#include "queue/sqlite_journal.h"
#include "queue/submitter.h"
#include "queue_crash_protocol.h"
#include "store/group_commit_writer.h"
#include "store/store.h"

namespace {

using namespace acomms;
namespace crash = testing::queue_crash;

std::mutex out_mutex;

// One write(2) per line, straight to the file: nothing sits in a stdio
// buffer to be lost by SIGKILL, and lines never interleave.
void say(const std::string& line) {
  std::lock_guard lock(out_mutex);
  std::string text = line + "\n";
  size_t done = 0;
  while (done < text.size()) {
    ssize_t n = ::write(STDOUT_FILENO, text.data() + done, text.size() - done);
    if (n <= 0) std::_Exit(3);
    done += static_cast<size_t>(n);
  }
}

void submit_forever(const dccl::Codec& codec, queue::QueueManager& queues, queue::Submitter& submitter,
                    core::EventLoop& core, queue::SqliteJournal& journal, int thread) {
  auto message = codec.new_message(crash::kType);
  const auto* type = message->GetDescriptor();
  const auto* reflection = message->GetReflection();
  reflection->SetInt32(message.get(), type->FindFieldByName("thread"), thread);
  reflection->SetString(message.get(), type->FindFieldByName("filler"), std::string("\0\xff", 2) + "filler");
  for (int64_t seq = 0;; ++seq) {
    reflection->SetInt64(message.get(), type->FindFieldByName("seq"), seq);
    std::promise<queue::SubmitResult> answered;
    std::future<queue::SubmitResult> answer = answered.get_future();
    submitter.submit(*message, 0, [&answered](queue::SubmitResult result) { answered.set_value(std::move(result)); });
    queue::SubmitResult result = answer.get();  // durable and queued once answered
    if (!result.ok()) std::_Exit(4);
    int64_t id = result.message_id;
    say("ok " + std::to_string(id) + " " + std::to_string(thread) + " " + std::to_string(seq));
    if (seq % crash::kRemoveEvery == 0) {
      if (!core.call([&] { return queues.cancel(id, "crash test"); })) std::_Exit(5);
      journal.flush();
      say("removed " + std::to_string(id));
    }
  }
}

// Receive mode: crash.Test{thread: 0, seq: 0, 1, ...} arrives from node 2
// through QueueManager::receive, one message a core-thread turn, and each
// asks for its ACK exactly as the link's software ACKs do
// (queue::durable_receipts, the daemon's hook); "acked <seq>" is printed
// when that ACK would go on the air.
void receive_forever(const dccl::Codec& codec, queue::QueueManager& queues, core::EventLoop& core,
                     queue::SqliteJournal& journal) {
  queue::AfterReceiptsDurable after_durable =
      queue::durable_receipts(journal, [&core](queue::Task task) { core.post(std::move(task)); });
  auto message = codec.new_message(crash::kType);
  const auto* type = message->GetDescriptor();
  const auto* reflection = message->GetReflection();
  reflection->SetString(message.get(), type->FindFieldByName("filler"), "received");
  std::function<void(int64_t)> receive = [&](int64_t seq) {
    reflection->SetInt64(message.get(), type->FindFieldByName("seq"), seq);
    if (queues.receive(codec.encode(*message), 2).size() != 1) std::_Exit(6);
    after_durable([seq] { say("acked " + std::to_string(seq)); });
    core.post([&receive, seq] { receive(seq + 1); });
  };
  core.call([&] { receive(0); });
  for (;;) ::pause();  // until killed
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: queue_crash_child <data dir> <threads> <proto file>\n");
    return 2;
  }
  // Never outlive a test runner that died before killing us.
  ::alarm(30);
  // stdout carries the protocol: logs go to stderr.
  spdlog::set_default_logger(spdlog::stderr_logger_mt("queue_crash_child"));
  spdlog::set_level(spdlog::level::err);
  std::string dir = argv[1];
  const bool receiving = std::string(argv[2]) == "receive";
  int threads = receiving ? 0 : std::atoi(argv[2]);

  store::Store store(dir);
  store::GroupCommitWriter writer(store.db());
  queue::SqliteJournal journal(writer);
  dccl::Codec codec;
  codec.load(argv[3]);
  v1::QueueConfig config;
  google::protobuf::TextFormat::ParseFromString(crash::kQueueConfig, &config);
  core::SystemClock clock;
  queue::QueueManager queues(codec, config, 1, clock, journal);
  queues.restore();
  core::EventLoop core;
  queue::Submitter submitter(queues, [&core](std::function<void()> work) { core.post(std::move(work)); });
  core.start();
  say("ready");
  if (receiving) receive_forever(codec, queues, core, journal);
  std::vector<std::thread> submitters;
  for (int t = 0; t < threads; ++t) {
    submitters.emplace_back([&, t] { submit_forever(codec, queues, submitter, core, journal, t); });
  }
  for (auto& submitter : submitters) submitter.join();  // until killed
}
