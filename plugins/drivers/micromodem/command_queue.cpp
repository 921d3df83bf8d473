#include "micromodem/command_queue.h"

#include "core/core_thread.h"

namespace acomms::drivers::micromodem {

using ::acomms::micromodem::ModemError;
using ::acomms::micromodem::Sentence;

CommandQueue::CommandQueue(core::Scheduler& scheduler, std::function<void(const Sentence&)> write,
                           Duration timeout)
    : scheduler_(scheduler), write_(std::move(write)), timeout_(timeout) {}

CommandQueue::~CommandQueue() {
  if (timer_ != 0) scheduler_.cancel(timer_);
}

void CommandQueue::push(Command command) {
  ACOMMS_ASSERT_CORE_THREAD();
  queue_.push_back(std::move(command));
  if (queue_.size() == 1) {
    tries_used_ = 0;
    send_current();
  }
}

void CommandQueue::send_current() {
  ++generation_;
  ++tries_used_;
  uint64_t generation = generation_;
  if (timer_ != 0) scheduler_.cancel(timer_);
  timer_ = scheduler_.after(timeout_, [this, generation] { on_timeout(generation); });
  // Written last: a test port may answer synchronously.
  write_(queue_.front().sentence);
}

void CommandQueue::on_timeout(uint64_t generation) {
  timer_ = 0;
  if (generation != generation_ || queue_.empty()) return;
  if (tries_used_ < queue_.front().tries) return send_current();
  finish(false, nullptr,
         "no reply to " + queue_.front().sentence.address() + " after " + std::to_string(tries_used_) +
             (tries_used_ == 1 ? " try" : " tries"));
}

bool CommandQueue::on_sentence(const Sentence& sentence) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (queue_.empty() || !queue_.front().is_reply || !queue_.front().is_reply(sentence)) return false;
  finish(true, &sentence, "");
  return true;
}

bool CommandQueue::on_error(const ModemError& error) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (queue_.empty() || error.module != "NMEA") return false;
  finish(false, nullptr,
         "the modem refused " + ::acomms::micromodem::serialize(queue_.front().sentence) + ": " + error.message);
  return true;
}

void CommandQueue::clear(const std::string& why) {
  std::deque<Command> failed = std::move(queue_);
  queue_.clear();
  ++generation_;
  if (timer_ != 0) scheduler_.cancel(timer_);
  timer_ = 0;
  for (Command& command : failed) {
    if (command.done) command.done(false, nullptr, why);
  }
}

void CommandQueue::finish(bool ok, const Sentence* reply, const std::string& why) {
  Command command = std::move(queue_.front());
  queue_.pop_front();
  ++generation_;
  if (timer_ != 0) scheduler_.cancel(timer_);
  timer_ = 0;
  consecutive_failures_ = ok ? 0 : consecutive_failures_ + 1;
  if (!queue_.empty()) {
    tries_used_ = 0;
    send_current();
  }
  // After the next command went out: `done` may push more (they queue behind).
  if (command.done) command.done(ok, reply, why);
}

}  // namespace acomms::drivers::micromodem
