#pragma once
// The water between simulated modems, as one node sees it: what it sends
// goes to every other node, and what the others send comes back as
// envelopes. Physics (delay, loss, collisions, half-duplex) is not done
// here but by each receiving SimDriver, so that both media behave alike:
// SimChannel (nodes in one process) and LoopbackMedium (nodes in several
// processes over loopback UDP).

#include <cstdint>
#include <functional>
#include <string>

#include "sim/sim_envelope.h"

namespace acomms::drivers {

class SimMedium {
 public:
  using Listener = std::function<void(const SimEnvelope& envelope)>;
  // Every datagram as it arrived (loopback only), for on_raw.
  using RawListener = std::function<void(std::string_view bytes)>;
  virtual ~SimMedium() = default;

  // Begins passing what other nodes send to `listener`. Throws DriverError
  // when the medium cannot be opened (the loopback address is taken).
  virtual void open(Listener listener, RawListener raw = nullptr) = 0;
  // Stops; no listener runs after it returns.
  virtual void close() = 0;
  // Tells every other node. Returns "" or a problem worth a log line.
  virtual std::string send(const SimEnvelope& envelope) = 0;
  // Malformed datagrams received and dropped so far.
  virtual uint64_t garbage_received() const { return 0; }
};

}  // namespace acomms::drivers
