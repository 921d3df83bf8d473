#pragma once
// The Micro-Modem's own acknowledgements of our last DATA packet.
//
// The problem: the destination's modem acknowledges by itself, one `$CAACK`
// per frame, then a `$CACST` for the ACK mini-packet (spec §5.7). MM1 may
// report ACKs between two other modems as if for us (§10 quirk 8); blank
// frames and duplicates get ACKs too (quirk 9). The link controller
// forgets a destination's frames at the first ACK it is given, so the ACKs
// of one packet must reach it as one ACK transmission.
// The decision: after a unicast packet that asked for ACKs has gone, the
// tracker expects ACKs from its destination for its non-empty frames until
// a deadline (spec §9). A `$CAACK` counts only with DEST = us, SRC = that
// destination and a frame still awaited; the batch is delivered at the
// next `$CACST` (or at the deadline), as acked_frame = F - 1.
//
// Core thread only.

#include <cstdint>
#include <functional>
#include <set>

#include "acomms/v1/modem_transmission.pb.h"
#include "core/scheduler.h"
#include "micromodem/nmea/receive_sentences.h"

namespace acomms::drivers::micromodem {

class AckTracker {
 public:
  struct Counters {
    uint64_t accepted = 0;  // $CAACK counted for our frames
    uint64_t ignored = 0;   // third-party, duplicate, or for frames we did not fill
    uint64_t expired = 0;   // packets whose ACKs did not all come before the deadline
  };

  AckTracker(core::Scheduler& scheduler, int own_id, std::function<void(const v1::ModemTransmission&)> deliver);
  ~AckTracker();

  // `sent` went out (frames as supplied); expect ACKs until now + `wait`.
  void expect(const v1::ModemTransmission& sent, std::chrono::system_clock::duration wait);
  void on_ack(const ::acomms::micromodem::Acknowledgement& ack);
  // A $CACST: the ACK mini-packet is complete.
  void on_statistics();
  void reset();

  bool awaiting() const { return !awaited_.empty(); }
  const Counters& counters() const { return counters_; }

 private:
  void flush();

  core::Scheduler& scheduler_;
  int own_id_;
  std::function<void(const v1::ModemTransmission&)> deliver_;
  int destination_ = -1;
  int rate_ = 0;
  std::set<int> awaited_;  // wire frame numbers (from 1)
  std::set<int> batch_;
  core::Scheduler::TaskId timer_ = 0;
  Counters counters_;
};

}  // namespace acomms::drivers::micromodem
