#pragma once
// A message taken off the link, as Subscribe streams it.
//
// Thread-safe: a pure conversion.

#include "acomms/v1/acomms.pb.h"
#include "acomms/v1/modem_transmission.pb.h"
#include "queue/queue_manager.h"

namespace acomms::service {

v1::ReceivedMessage to_received_message(const queue::ReceivedMessage& message,
                                        const v1::ModemTransmission& transmission);

}  // namespace acomms::service
