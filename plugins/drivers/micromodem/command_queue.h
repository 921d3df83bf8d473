#pragma once
// One command to the modem at a time, each waiting for its reply.
//
// The problem: the modem executes commands one by one and a flood can
// overrun its input (spec §2.4, §10 quirk 13); NVRAM writes take ~0.1 s
// each and are confirmed by an echo that must match name and value. The
// decision (goby3's policy, spec §2.4): send one command, wait for the
// reply its `is_reply` recognises, resend after `timeout` up to `tries`
// times, then give up on it; a `$CAERR` with module NMEA (the firmware
// refuses or does not know the command, or the checksum was bad) fails the
// current command at once. Consecutive failures are counted: the driver
// declares the modem dead after five (spec §9).
//
// Commands that must never be repeated ($CCCYC, $CCTXD: a late one is sent
// with the next cycle, §10 quirk 5) are pushed with tries = 1.
//
// Core thread only (the scheduler's thread).

#include <chrono>
#include <deque>
#include <functional>
#include <string>

#include "core/scheduler.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::drivers::micromodem {

using Duration = std::chrono::system_clock::duration;

struct Command {
  ::acomms::micromodem::Sentence sentence;
  // True for the sentence that answers this command.
  std::function<bool(const ::acomms::micromodem::Sentence&)> is_reply;
  // Once: ok with the reply, or not ok with why ("no reply after 3 tries").
  std::function<void(bool ok, const ::acomms::micromodem::Sentence* reply, const std::string& why)> done;
  int tries = 3;
};

class CommandQueue {
 public:
  // `write` puts one sentence on the port (checksum and line end added there).
  CommandQueue(core::Scheduler& scheduler, std::function<void(const ::acomms::micromodem::Sentence&)> write,
               Duration timeout);
  ~CommandQueue();

  void push(Command command);
  // A sentence from the modem: true when it answered the current command.
  bool on_sentence(const ::acomms::micromodem::Sentence& sentence);
  // A $CAERR from the modem: fails the current command when it refuses a
  // command (module NMEA). True when it did.
  bool on_error(const ::acomms::micromodem::ModemError& error);
  // Fails every queued command with `why` (a reboot, stop()).
  void clear(const std::string& why);

  bool idle() const { return queue_.empty(); }
  int consecutive_failures() const { return consecutive_failures_; }
  void set_timeout(Duration timeout) { timeout_ = timeout; }

 private:
  void send_current();
  void on_timeout(uint64_t generation);
  void finish(bool ok, const ::acomms::micromodem::Sentence* reply, const std::string& why);

  core::Scheduler& scheduler_;
  std::function<void(const ::acomms::micromodem::Sentence&)> write_;
  Duration timeout_;
  std::deque<Command> queue_;
  int tries_used_ = 0;
  uint64_t generation_ = 0;  // tells a stale timer from the current command's
  core::Scheduler::TaskId timer_ = 0;
  int consecutive_failures_ = 0;
};

}  // namespace acomms::drivers::micromodem
