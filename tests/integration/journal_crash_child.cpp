// The process journal_crash_test kills: appends from several threads as fast
// as it can and reports, on stdout, only what the journal has confirmed. See
// journal_crash_protocol.h for what it prints.
//
//   journal_crash_child <data dir> <threads>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>

#include "journal_crash_protocol.h"
#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"

namespace {

using namespace acomms;
using testing::journal_crash::kRemoveEvery;
using testing::journal_crash::payload;

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

void append_forever(queue::SqliteJournal& journal, int thread) {
  for (int64_t seq = 0;; ++seq) {
    queue::JournalMessage message;
    message.type = "crash.Test";
    message.payload = payload(thread, seq);
    message.src = thread;
    message.dest = 0;
    message.submitted_at = 1'700'000'000.0 + static_cast<double>(seq);
    int64_t id = journal.append(std::move(message));
    say("ok " + std::to_string(id) + " " + std::to_string(thread) + " " + std::to_string(seq));
    if (seq % kRemoveEvery == 0) {
      queue::QueueEvent acked;
      acked.kind = queue::QueueEventKind::kAcked;
      acked.type = "crash.Test";
      acked.message_id = id;
      acked.removes_message = true;
      journal.record(acked);
      journal.flush();
      say("removed " + std::to_string(id));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: journal_crash_child <data dir> <threads>\n");
    return 2;
  }
  // Never outlive a test runner that died before killing us.
  ::alarm(30);
  spdlog::set_level(spdlog::level::warn);
  std::string dir = argv[1];
  int threads = std::atoi(argv[2]);
  store::Store store(dir);
  store::GroupCommitWriter writer(store.db());
  queue::SqliteJournal journal(writer);
  say("ready");
  std::vector<std::thread> appenders;
  for (int t = 0; t < threads; ++t) {
    appenders.emplace_back([&journal, t] { append_forever(journal, t); });
  }
  for (auto& appender : appenders) appender.join();  // until killed
}
