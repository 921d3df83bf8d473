#include "node/received_message_router.h"

#include <spdlog/spdlog.h>

#include <memory>

#include "service/received_message.h"
#include "telemetry/wire_message.h"

namespace acomms::node {

ReceivedMessageRouter::ReceivedMessageRouter(ToTelemetry telemetry, queue::WhenStored when_stored,
                                             Publish publish, Later later)
    : telemetry_(std::move(telemetry)),
      when_stored_(std::move(when_stored)),
      publish_(std::move(publish)),
      later_(std::move(later)) {}

void ReceivedMessageRouter::route(queue::ReceivedMessage message, const v1::ModemTransmission& from) {
  spdlog::debug("received {} from {} (transmission from {})", message.type, message.src, from.src());
  if (telemetry::is_telemetry_type(message.type)) {
    // After the rest of the transmission (the file comment says why).
    auto held = std::make_shared<queue::ReceivedMessage>(std::move(message));
    later_([telemetry = telemetry_, held] { telemetry(*held); });
    return;
  }
  // Built now: `message` is gone by the time its event is committed.
  auto received = std::make_shared<const v1::ReceivedMessage>(service::to_received_message(message, from));
  when_stored_([publish = publish_, received](std::exception_ptr error) {
    if (error) {
      spdlog::error("received message {} (seq {}) may not be stored; passed on anyway", received->type(),
                    received->seq());
    }
    publish(*received);
  });
}

}  // namespace acomms::node
