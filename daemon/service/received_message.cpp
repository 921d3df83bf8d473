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
  return out;
}

}  // namespace acomms::service
