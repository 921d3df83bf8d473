#pragma once
// The DirectIP MO server: the gateway connects, sends one MO message and
// waits for us to close (or, when provisioned, for an MO confirmation:
// spec §9.2).
//
// The problem: the port faces the Internet, the gateway retries for hours
// whatever we do, and an MO the gateway thinks delivered must never be lost.
// The decisions:
//  - bounded: at most max_connections at once (more wait in the kernel's
//    backlog, not in our memory); each reads 3 bytes, then exactly the
//    overall length N (≤ directip::kMaxOverallLength, checked before
//    reading it), within read_timeout for the whole message, or is dropped;
//  - the connection is answered and closed only when the owner says so
//    (Finish), which the driver does once the MO is durable; an owner that
//    never does is cut off after kHoldLimit, without an answer, so that a
//    broken store cannot pin connections forever (the gateway redelivers).
//
// Core thread only: runs on the io_context it is given, every callback
// runs there, and no callback runs after close().

#include <asio/io_context.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "iridium_shore/iridium_shore_settings.h"

namespace acomms::drivers {

class MoServer {
 public:
  // Writes `reply` (empty: nothing) and closes the connection. Once only;
  // a no-op when the connection is already gone.
  using Finish = std::function<void(std::string reply)>;
  // One whole message as read: the prefix and N bytes (not yet parsed).
  using OnMessage = std::function<void(std::string message, Finish finish)>;
  // A connection dropped for bad input ("MO read timeout", "MO prefix
  // refused"), with a detail for the log.
  using OnBadInput = std::function<void(const std::string& kind, const std::string& detail)>;

  static constexpr std::chrono::seconds kHoldLimit{60};

  // `listen` is where to bind; `label` names it in errors and logs.
  MoServer(asio::io_context& context, HostAndPort listen, std::string label, uint32_t max_connections,
           std::chrono::milliseconds read_timeout);
  ~MoServer();  // closes
  MoServer(const MoServer&) = delete;
  MoServer& operator=(const MoServer&) = delete;

  // Binds and starts accepting. Throws link::DriverError naming the
  // address when it cannot bind.
  void open(OnMessage on_message, OnBadInput on_bad_input);
  // Stops accepting and drops every connection (unanswered). Idempotent.
  void close();
  // The bound port (useful with port 0); 0 when closed.
  uint16_t local_port() const;
  // Connections open now.
  size_t connections() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace acomms::drivers
