#pragma once
// What every driver does the same way with a ModemTransmission, so that the
// simulator, the UDP link and real modems behave alike for the MAC and the
// queues (see driver.h):
//  - a request whose src is another node is a poll of that node;
//  - our own DATA gets the rate's frame limits before the data request and
//    must fit them after it;
//  - DATA addressed to us with ack_requested is acknowledged in software by
//    an ACK listing the frames that arrived;
//  - a DATA transmission without frames heard with our own id as src is a
//    poll for us: we answer with our data. (Nobody else sends with our src,
//    so this needs no extra field on the wire.)
//
// Thread-safe: pure functions of their arguments.

#include <cstdint>
#include <string>

#include "acomms/v1/config.pb.h"
#include "acomms/v1/modem_transmission.pb.h"

namespace acomms::link {

// The node's modem id from the config: 0 (unset) means 1.
int32_t own_modem_id(const v1::DriverConfig& config);

// initiate_transmission(): does `request` ask us to poll node request.src()?
bool is_poll_request(const v1::ModemTransmission& request, int32_t own_id);

// Prepares our own DATA transmission for the data request: src, type,
// max_num_frames and max_frame_bytes (the overrides when nonzero, else the
// rate table; a smaller max_num_frames the request already carries stays).
// Returns an error ("rate 9 is not in 0..5") or "".
std::string prepare_data(v1::ModemTransmission* transmission, int32_t own_id,
                         uint32_t max_frame_bytes_override = 0, uint32_t max_num_frames_override = 0);

// After the data request: "" when the frames fit the limits, else why not.
std::string check_frames(const v1::ModemTransmission& transmission);

// A received transmission: is it DATA for us that asks for an ACK?
bool wants_ack(const v1::ModemTransmission& received, int32_t own_id);
// The software ACK for `received` (all its frames arrived intact).
v1::ModemTransmission make_ack(const v1::ModemTransmission& received, int32_t own_id);

// A received transmission: is it a poll asking us to send?
bool is_poll_for(const v1::ModemTransmission& received, int32_t own_id);
// What a polled node sends: its own DATA to the poll's dest, at its rate,
// with the poll's slot_seconds and max_num_frames and, when the poll has a time (the end of
// its reception), time = the start of its reception (kMiniPacket earlier).
v1::ModemTransmission make_poll_response(const v1::ModemTransmission& poll, int32_t own_id);

// A received transmission: should on_receive see it? DATA with frames
// (for anyone: the queues filter by dest), ACKs for us, driver-specific.
bool should_report(const v1::ModemTransmission& received, int32_t own_id);

}  // namespace acomms::link
