#include "service/received_message.h"

#include "dccl/message_json.h"
#include "link/link_figures.h"

namespace acomms::service {

v1::ReceivedMessage to_received_message(const queue::ReceivedMessage& message,
                                        const v1::ModemTransmission& transmission) {
  v1::ReceivedMessage out;
  out.set_type(message.type);
  out.set_payload(message.message->SerializePartialAsString());
  out.set_json(dccl::message_json(*message.message));
  out.set_src(message.src);
  out.set_dest(message.dest);
  out.set_receive_time(message.time);
  out.set_seq(message.seq);
  *out.mutable_link() = link::link_figures(transmission);
  return out;
}

}  // namespace acomms::service
