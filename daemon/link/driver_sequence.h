#pragma once
// The transmit and receive sequence every driver runs, written once.
//
// The problem: driver.h promises the MAC and the queues that every link
// behaves alike, and each driver used to spell that promise out itself:
// a request under another node's id is a poll; our own DATA gets the rate's
// frame limits, asks the queues for frames (on_data_request), fails with
// "nothing to send" when they give none, and goes out to broadcast when they
// chose no destination; a poll for us is answered with our DATA; what the
// queues should see is reported; DATA to us with ack_requested is
// acknowledged in software. Two copies drift, and the Micro-Modem would
// have made three.
//
// The decision: a driver owns a DriverSequence (composition, not a base
// class) and gives it the one thing that differs, how a transmission goes on
// its medium (Medium::send), plus, per heard packet, how soon it may answer.
// The sequence makes every decision above, reports failures through
// on_transmit_result, and owns the driver's callbacks between start() and
// stop(). transmission_rules.h holds the single rules it applies.
//
// Variants the drivers choose through Options: the frame limits (the rate
// table, or the driver's overrides: udp), and software_acks, false for
// modems that acknowledge in hardware. The Micro-Modem is such a modem: its
// Medium::send starts the cycle ($CCCYC) with the frames the sequence got
// from the queues and hands them out as the modem asks for each ($CADRQ),
// and the modem's own ACKs come back through on_received. A hardware ACK
// goes out when the modem decides, before the store has committed what it
// acknowledges; only software ACKs wait for that (README, "Acknowledgements
// and crashes").
//
// Invariants: nothing reaches a callback before start() or after stop(); a
// transmission the MAC started is answered by on_transmit_result exactly
// once (failures here, success by the driver once it has gone); transmitting,
// receiving and reporting run on the core thread (asserted).

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "acomms/v1/modem_transmission.pb.h"
#include "link/driver.h"

namespace acomms::link {

class DriverSequence {
 public:
  struct Options {
    // Names the driver in errors and logs: "sim modem 3".
    std::string label;
    int32_t own_id = 1;
    // Frame limits offered to the queues; 0: the rate table's.
    uint32_t max_frame_bytes = 0;
    uint32_t max_num_frames = 0;
    bool software_acks = true;
  };

  // What the driver does for the sequence.
  struct Medium {
    // Puts `transmission` on the medium now (a poll, an ACK, other non-DATA,
    // or DATA with its frames). Returns "" when it goes out, else why not
    // ("busy transmitting until ..."). When `report` (the MAC or a poll asked
    // for it), the driver calls report(transmission, true, "") once it has
    // gone: at once, or when the packet is all in the water. ACKs go with
    // report false and their failures are the driver's to log.
    std::function<std::string(const v1::ModemTransmission& transmission, bool report)> send;
  };

  // What the driver knows about one packet it heard.
  struct Heard {
    // The node that really sent it, when the medium says (the simulator's
    // envelope): DATA under another id is then a poll of that node. Unset:
    // DATA without frames under our own id is a poll for us.
    std::optional<int32_t> sender;
    // Runs an answer (our DATA for a poll, a software ACK) when this node may
    // transmit: after the modem's turnaround, once it is not transmitting.
    // Null: at once.
    std::function<void(std::function<void()> answer)> answer_when_free;
  };

  DriverSequence(Options options, Medium medium);
  // Answers waiting for the store or the medium hold `this`: a copy or a
  // move would leave them on the wrong object.
  DriverSequence(const DriverSequence&) = delete;
  DriverSequence& operator=(const DriverSequence&) = delete;

  // Begins reporting through `callbacks`; stop() clears them. Idempotent.
  void start(DriverCallbacks callbacks);
  void stop();
  bool running() const { return running_; }
  // Throws DriverError "<label> is not started" unless running.
  void check_running() const;
  const DriverCallbacks& callbacks() const { return callbacks_; }

  // Driver::initiate_transmission: a poll goes out as a frameless DATA under
  // the polled node's id, other non-DATA as is, our own DATA through
  // send_data(). Throws DriverError when not started.
  void transmit(const v1::ModemTransmission& request);
  // Our own DATA (the MAC's, or the answer to a poll): frames from the
  // queues, then the medium; failures are reported.
  void send_data(v1::ModemTransmission transmission);
  // Limits for the rate, the queues' frames, and the checks on them.
  // Returns "" or why nothing can be sent ("nothing to send: ...").
  std::string request_frames(v1::ModemTransmission* transmission);

  // A packet heard from the medium (parsed, time set): polls for us are
  // answered, what the queues should see goes to on_receive, and DATA to us
  // with ack_requested is acknowledged (software_acks) once what it carried
  // is durable (DriverCallbacks::after_receipt_durable).
  void on_received(const v1::ModemTransmission& received, const Heard& heard = {});

  // Reports a transmission's result to on_transmit_result (failures logged).
  void report(const v1::ModemTransmission& transmission, bool ok, const std::string& error);

 private:
  void send_reported(const v1::ModemTransmission& transmission);

  Options options_;
  Medium medium_;
  DriverCallbacks callbacks_;
  bool running_ = false;
  // Expires with the sequence: an ACK waiting for the store checks it
  // before touching the sequence (or its driver) again.
  std::shared_ptr<const char> alive_ = std::make_shared<const char>(0);
};

}  // namespace acomms::link
