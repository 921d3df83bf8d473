#include "link/driver_sequence.h"

#include <spdlog/spdlog.h>

#include "core/core_thread.h"
#include "link/transmission_rules.h"

namespace acomms::link {

using v1::ModemTransmission;

DriverSequence::DriverSequence(Options options, Medium medium)
    : options_(std::move(options)), medium_(std::move(medium)) {}

void DriverSequence::start(DriverCallbacks callbacks) {
  callbacks_ = std::move(callbacks);
  running_ = true;
}

void DriverSequence::stop() {
  running_ = false;
  callbacks_ = {};
}

void DriverSequence::check_running() const {
  if (!running_) throw DriverError(options_.label + " is not started");
}

void DriverSequence::transmit(const ModemTransmission& request) {
  ACOMMS_ASSERT_CORE_THREAD();
  check_running();
  if (is_poll_request(request, options_.own_id)) {
    // Third-party initiation: a frameless DATA that tells node src to send.
    ModemTransmission poll = request;
    poll.clear_frame();
    poll.set_type(ModemTransmission::DATA);
    send_reported(poll);
    return;
  }
  if (request.type() != ModemTransmission::DATA) {
    send_reported(request);
    return;
  }
  send_data(request);
}

void DriverSequence::send_data(ModemTransmission transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  std::string error = request_frames(&transmission);
  if (!error.empty()) return report(transmission, false, error);
  if (transmission.dest() < 0) transmission.set_dest(0);  // the queues did not choose: broadcast
  send_reported(transmission);
}

std::string DriverSequence::request_frames(ModemTransmission* transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  std::string error =
      prepare_data(transmission, options_.own_id, options_.max_frame_bytes, options_.max_num_frames);
  if (!error.empty()) return error;
  if (callbacks_.on_data_request) callbacks_.on_data_request(transmission);
  error = check_frames(*transmission);
  if (error.empty() && transmission->frame_size() == 0) error = "nothing to send: the data request gave no frames";
  return error;
}

void DriverSequence::send_reported(const ModemTransmission& transmission) {
  std::string error = medium_.send(transmission, /*report=*/true);
  if (!error.empty()) report(transmission, false, error);
}

void DriverSequence::on_received(const ModemTransmission& received, const Heard& heard) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!running_) return;
  const int32_t own_id = options_.own_id;
  auto answer = [&heard](std::function<void()> send) {
    if (heard.answer_when_free) {
      heard.answer_when_free(std::move(send));
    } else {
      send();
    }
  };
  // With the real sender known, DATA under another id is a poll (of that
  // id's node); without it, only our own id on frameless DATA says so.
  bool poll = heard.sender ? received.type() == ModemTransmission::DATA && received.src() != *heard.sender
                           : is_poll_for(received, own_id);
  if (poll) {
    if (received.src() == own_id) {
      answer([this, response = make_poll_response(received, own_id)] { send_data(response); });
    }
    return;
  }
  if (should_report(received, own_id) && callbacks_.on_receive) callbacks_.on_receive(received);
  // on_receive may have stopped the driver: then nothing more goes out.
  if (!options_.software_acks || !running_ || !wants_ack(received, own_id)) return;
  // Only once what on_receive passed on is durable (DriverCallbacks), and
  // only if this sequence still runs then: the driver may have been stopped
  // or destroyed while the store committed.
  auto acknowledge = [this, alive = std::weak_ptr<const char>(alive_), ack = make_ack(received, own_id),
                      when_free = heard.answer_when_free] {
    if (alive.expired() || !running_) return;
    auto send = [this, ack] { medium_.send(ack, /*report=*/false); };
    if (when_free) {
      when_free(std::move(send));
    } else {
      send();
    }
  };
  if (callbacks_.after_receipt_durable) {
    callbacks_.after_receipt_durable(std::move(acknowledge));
  } else {
    acknowledge();
  }
}

void DriverSequence::report(const ModemTransmission& transmission, bool ok, const std::string& error) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!ok) spdlog::warn("{}: transmission not sent: {}", options_.label, error);
  if (callbacks_.on_transmit_result) callbacks_.on_transmit_result(transmission, ok, error);
}

}  // namespace acomms::link
