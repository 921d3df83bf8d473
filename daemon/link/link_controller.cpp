#include "link/link_controller.h"

#include <spdlog/spdlog.h>

#include "core/core_thread.h"

namespace acomms::link {

LinkController::LinkController(int32_t own_id, queue::QueueManager& queues, mac::Mac& mac, Driver& driver,
                               Deliver deliver)
    : own_id_(own_id), queues_(queues), mac_(mac), driver_(driver), deliver_(std::move(deliver)) {}

void LinkController::start() {
  ACOMMS_ASSERT_CORE_THREAD();
  DriverCallbacks callbacks;
  callbacks.on_receive = [this](const v1::ModemTransmission& t) { on_receive(t); };
  callbacks.on_data_request = [this](v1::ModemTransmission* t) { on_data_request(t); };
  callbacks.on_transmit_result = [this](const v1::ModemTransmission& t, bool ok, const std::string& error) {
    on_transmit_result(t, ok, error);
  };
  callbacks.on_raw = [this](std::string_view bytes, bool outgoing) {
    if (raw_tap_) raw_tap_(bytes, outgoing);
    if (spdlog::should_log(spdlog::level::trace)) {
      spdlog::trace("link {} {} bytes", outgoing ? ">>" : "<<", bytes.size());
    }
  };
  driver_.start(std::move(callbacks));
  mac_.start([this](const v1::ModemTransmission& t) {
    try {
      driver_.initiate_transmission(t);
    } catch (const DriverError& e) {
      ++stats_.transmissions_failed;
      spdlog::warn("link: slot for node {} lost: {}", t.src(), e.what());
    }
  });
}

void LinkController::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  mac_.stop();
  driver_.stop();
}

void LinkController::on_data_request(v1::ModemTransmission* transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  queue::DataRequest request;
  request.dest = transmission->has_dest() ? transmission->dest() : queue::kAnyDestination;
  request.max_frame_bytes = transmission->max_frame_bytes();
  request.max_num_frames = transmission->max_num_frames();
  request.ack_requested = transmission->ack_requested();
  std::vector<queue::Frame> frames = queues_.build_frames(request);
  transmission->clear_frame();
  std::vector<uint64_t> frame_ids;
  bool ack = false;
  for (queue::Frame& frame : frames) {
    transmission->add_frame(std::move(frame.bytes));
    frame_ids.push_back(frame.frame_id);
    ack = ack || frame.ack_requested;
  }
  // With nothing to send the slot is still used: one empty frame, to
  // broadcast, unacked. Being heard in its slot is how auto-discovery
  // neighbours learn that a node exists (a transmission without frames
  // would be a poll).
  if (frames.empty()) transmission->add_frame("");
  int32_t dest = frames.empty() ? queue::kBroadcast : frames.front().dest;
  if (request.dest == queue::kAnyDestination) transmission->set_dest(dest);
  transmission->set_ack_requested(ack);
  if (ack) awaiting_ack_[transmission->dest()] = std::move(frame_ids);
}

void LinkController::on_receive(const v1::ModemTransmission& transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  mac_.on_receive(transmission);
  if (transmission.type() == v1::ModemTransmission::ACK) {
    if (transmission.dest() != own_id_) return;
    ++stats_.acks_received;
    auto it = awaiting_ack_.find(transmission.src());
    if (it == awaiting_ack_.end()) {
      spdlog::debug("link: ack from {} for nothing we sent it", transmission.src());
      return;
    }
    for (uint32_t index : transmission.acked_frame()) {
      if (index < it->second.size()) queues_.on_ack(it->second[index]);
    }
    awaiting_ack_.erase(it);
    return;
  }
  if (transmission.type() != v1::ModemTransmission::DATA) return;
  ++stats_.data_received;
  if (transmission.has_figures()) {
    ++stats_.receptions_with_figures;
    stats_.bad_frames_received += transmission.figures().bad_frames();
  }
  // Frames are filtered message by message (destination roles), not by the
  // transmission's dest: a unicast frame may carry broadcast messages.
  for (const std::string& frame : transmission.frame()) {
    for (queue::ReceivedMessage& message : queues_.receive(frame, transmission.src())) {
      ++stats_.messages_delivered;
      deliver_(std::move(message), transmission);
    }
  }
}

void LinkController::on_transmit_result(const v1::ModemTransmission& transmission, bool ok,
                                        const std::string& error) {
  if (ok) {
    ++stats_.transmissions_sent;
    return;
  }
  ++stats_.transmissions_failed;
  spdlog::warn("link: transmission to {} failed: {}", transmission.dest(), error);
}

}  // namespace acomms::link
