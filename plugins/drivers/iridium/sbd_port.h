#pragma once
// The byte stream to one Iridium modem, whatever carries it.
//
// The problem: the driver must run against a serial port, a serial-to-TCP
// gateway (a RockBLOCK on a networked serial server) and, in tests, a fake
// 9603 on the simulated scheduler with no file descriptor at all. The
// decision: the driver sees only this interface; transport_port() builds
// the real one from driver.iridium.port ("/dev/ttyUSB0" or "tcp:HOST:PORT"),
// tests plug in their own.
//
// Invariant: callbacks run on the core thread, never inside write(), and
// never after close() returns.

#include <asio/io_context.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "link/transport_state.h"

namespace acomms::drivers::iridium {

class SbdPort {
 public:
  using DataCallback = std::function<void(std::string_view bytes)>;
  virtual ~SbdPort() = default;
  // Starts delivering bytes; returns at once (the transport reopens by itself).
  virtual void open(DataCallback on_data, link::TransportStateCallback on_state) = 0;
  virtual void close() = 0;
  // Queues bytes for the modem; false (dropped) while the port is not open.
  virtual bool write(std::string_view bytes) = 0;
  // "/dev/ttyUSB0", "tcp:127.0.0.1:40001": for logs and errors.
  virtual std::string name() const = 0;
};

// A serial port (`port` a device path, at `baud`, RTS/CTS when `rts_cts`)
// or a TCP client ("tcp:HOST:PORT"). Throws std::invalid_argument for an
// empty or malformed port, naming driver.iridium.port.
std::unique_ptr<SbdPort> transport_port(const std::string& port, unsigned baud, bool rts_cts,
                                        asio::io_context& context);

}  // namespace acomms::drivers::iridium
