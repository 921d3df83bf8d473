#include "link/transmission_rules.h"

#include <algorithm>

#include "link/rate_table.h"

namespace acomms::link {

using v1::ModemTransmission;

int32_t own_modem_id(const v1::DriverConfig& config) {
  return config.modem_id() == 0 ? 1 : static_cast<int32_t>(config.modem_id());
}

bool is_poll_request(const ModemTransmission& request, int32_t own_id) {
  return request.type() == ModemTransmission::DATA && request.has_src() && request.src() >= 0 &&
         request.src() != own_id;
}

std::string prepare_data(ModemTransmission* tx, int32_t own_id, uint32_t max_frame_bytes_override,
                         uint32_t max_num_frames_override) {
  const ModemRate* rate = find_rate(tx->rate());
  if (rate == nullptr) {
    return "rate " + std::to_string(tx->rate()) + " is not in " + std::to_string(kMinRate) + ".." +
           std::to_string(kMaxRate);
  }
  tx->set_src(own_id);
  tx->set_type(ModemTransmission::DATA);
  uint32_t max_num_frames = max_num_frames_override ? max_num_frames_override : rate->max_num_frames;
  // A smaller limit the request already carries stands: the answer to a
  // poll that asked for fewer frames (Micro-Modem Nframes).
  if (tx->max_num_frames() > 0) max_num_frames = std::min(max_num_frames, tx->max_num_frames());
  tx->set_max_num_frames(max_num_frames);
  tx->set_max_frame_bytes(max_frame_bytes_override ? max_frame_bytes_override : rate->max_frame_bytes);
  return "";
}

std::string check_frames(const ModemTransmission& tx) {
  if (static_cast<uint32_t>(tx.frame_size()) > tx.max_num_frames()) {
    return "the data request gave " + std::to_string(tx.frame_size()) + " frames, rate " +
           std::to_string(tx.rate()) + " allows " + std::to_string(tx.max_num_frames());
  }
  for (int i = 0; i < tx.frame_size(); ++i) {
    if (tx.frame(i).size() > tx.max_frame_bytes()) {
      return "frame " + std::to_string(i) + " has " + std::to_string(tx.frame(i).size()) +
             " bytes, the limit is " + std::to_string(tx.max_frame_bytes());
    }
  }
  return "";
}

bool wants_ack(const ModemTransmission& rx, int32_t own_id) {
  return rx.type() == ModemTransmission::DATA && rx.dest() == own_id && rx.src() != own_id &&
         rx.ack_requested() && rx.frame_size() > 0;
}

ModemTransmission make_ack(const ModemTransmission& rx, int32_t own_id) {
  ModemTransmission ack;
  ack.set_type(ModemTransmission::ACK);
  ack.set_src(own_id);
  ack.set_dest(rx.src());
  ack.set_rate(rx.rate());
  ack.set_ack_requested(false);
  for (int i = 0; i < rx.frame_size(); ++i) ack.add_acked_frame(static_cast<uint32_t>(i));
  return ack;
}

bool is_poll_for(const ModemTransmission& rx, int32_t own_id) {
  // Without frames: our own DATA echoed back (a peer list naming ourselves)
  // must not make us answer ourselves.
  return rx.type() == ModemTransmission::DATA && rx.src() == own_id && rx.frame_size() == 0;
}

ModemTransmission make_poll_response(const ModemTransmission& poll, int32_t own_id) {
  ModemTransmission out;
  out.set_src(own_id);
  out.set_dest(poll.dest());
  out.set_rate(poll.rate());
  out.set_type(ModemTransmission::DATA);
  out.set_ack_requested(poll.ack_requested());
  if (poll.has_slot_seconds()) out.set_slot_seconds(poll.slot_seconds());
  if (poll.max_num_frames() > 0) out.set_max_num_frames(poll.max_num_frames());  // no more than it asked for
  // A poll as heard has the time its reception ended; the master's slot
  // began a mini-packet before that, and one travel time before that
  // again, which the link's slot budget allows for (link_controller.h).
  if (poll.time() > 0) {
    out.set_time(poll.time() - std::chrono::duration<double>(kMiniPacket).count());
  }
  return out;
}

bool should_report(const ModemTransmission& rx, int32_t own_id) {
  switch (rx.type()) {
    case ModemTransmission::DATA: return rx.src() != own_id && rx.frame_size() > 0;
    case ModemTransmission::ACK: return rx.dest() == own_id;
    default: return true;
  }
}

}  // namespace acomms::link
