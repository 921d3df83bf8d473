#include "sim/loopback_medium.h"

#include <spdlog/spdlog.h>

namespace acomms::drivers {

LoopbackMedium::LoopbackMedium(asio::io_context& context, const std::string& listen,
                               const std::vector<std::string>& peers)
    : transport_(context, listen, peers), listen_(listen) {}

void LoopbackMedium::open(Listener listener, RawListener raw) {
  transport_.open(
      [this, listener = std::move(listener), raw = std::move(raw)](std::string_view bytes, const std::string& from) {
        if (raw) raw(bytes);
        std::string error;
        auto envelope = decode_envelope(bytes, &error);
        if (!envelope) {
          // Anything may reach a UDP port; it must never hurt the node.
          ++garbage_;
          spdlog::warn("sim loopback {}: dropped a datagram from {} ({} bytes): {}", listen_, from,
                       bytes.size(), error);
          return;
        }
        listener(*envelope);
      });
}

void LoopbackMedium::close() { transport_.close(); }

std::string LoopbackMedium::send(const SimEnvelope& envelope) {
  return transport_.send_to_peers(encode(envelope));
}

}  // namespace acomms::drivers
