#pragma once
// The DirectIP MT client: one TCP connection per MT, to the gateway's MT
// port (spec §9.3, §9.5). It connects (within connect_timeout), sends the
// MT message, reads the MT confirmation (within confirmation_timeout) and
// closes.
//
// The gateway keeps an MT only if it sent its confirmation; a connection
// that fails before the confirmation leaves the outcome unknown to us, and
// the caller resubmits (the same MTMSN lets the vehicle drop a second copy:
// spec §9.3, §9.4).
//
// Core thread only: runs on the io_context it is given; `done` runs there,
// exactly once per submit, unless close() came first (then never).

#include <asio/io_context.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "iridium_shore/direct_ip.h"
#include "iridium_shore/iridium_shore_settings.h"

namespace acomms::drivers {

struct MtSubmitResult {
  // Set when the gateway answered with a well-formed confirmation.
  std::optional<directip::MtConfirmation> confirmation;
  // Otherwise why not: "connect to gw:10800 timed out", "the confirmation
  // is malformed: ...".
  std::string error;
  // The gateway answered with bytes that did not parse (bad input, counted
  // by the driver), rather than not at all.
  bool malformed = false;
};

class MtClient {
 public:
  // `gateway` is where to connect; `label` names it in errors ("host:port").
  MtClient(asio::io_context& context, HostAndPort gateway, std::string label, std::chrono::milliseconds connect_timeout,
           std::chrono::milliseconds confirmation_timeout);
  ~MtClient();  // closes
  MtClient(const MtClient&) = delete;
  MtClient& operator=(const MtClient&) = delete;

  // Sends one whole MT message (directip::build_mt) on a new connection.
  void submit(std::string message, std::function<void(MtSubmitResult)> done);
  // Abandons submissions in flight: their `done` never runs.
  void close();

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace acomms::drivers
