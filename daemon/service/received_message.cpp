#include "service/received_message.h"

#include "service/message_json.h"

namespace acomms::service {

v1::ReceivedMessage to_received_message(const queue::ReceivedMessage& message,
                                        const v1::ModemTransmission& transmission) {
  v1::ReceivedMessage out;
  out.set_type(message.type);
  out.set_payload(message.message->SerializePartialAsString());
  out.set_json(to_json(*message.message));
  out.set_src(message.src);
  out.set_dest(message.dest);
  out.set_receive_time(message.time);
  out.set_seq(message.seq);
  v1::LinkFigures* link = out.mutable_link();
  link->set_transmission_src(transmission.src());
  link->set_rate(transmission.rate());
  link->set_link_quality(transmission.link_quality());
  if (transmission.has_figures()) {
    const v1::ReceptionFigures& f = transmission.figures();
    if (f.has_snr_in_db()) link->set_snr_in_db(f.snr_in_db());
    if (f.has_snr_out_db()) link->set_snr_out_db(f.snr_out_db());
    if (f.has_signal_level_db()) link->set_signal_level_db(f.signal_level_db());
    if (f.has_mse_db()) link->set_mse_db(f.mse_db());
    if (f.has_doppler_mps()) link->set_doppler_mps(f.doppler_mps());
    if (f.has_delay_spread_s()) link->set_delay_spread_s(f.delay_spread_s());
    if (f.has_packet_type()) link->set_packet_type(f.packet_type());
    if (f.has_bad_frames()) link->set_bad_frames(f.bad_frames());
    if (f.has_noise_db()) link->set_noise_db(f.noise_db());
  }
  return out;
}

}  // namespace acomms::service
