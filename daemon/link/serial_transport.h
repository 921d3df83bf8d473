#pragma once
// A serial port (the usual way to talk to an acoustic modem): termios line
// settings through asio::serial_port. When the port fails (USB adapter
// unplugged, modem powered off) the transport closes it and keeps
// reopening it with exponential backoff, reporting each state change.
//
// Runs on the core thread's io_context; every callback runs there.

#include <asio/io_context.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "link/transport_state.h"

namespace acomms::link {

struct SerialSettings {
  std::string device;      // "/dev/ttyUSB0"
  unsigned baud = 19200;   // the Micro-Modem's default
  unsigned data_bits = 8;  // 8N1, no flow control: what modems speak
  bool hardware_flow_control = false;
  // De-assert RTS right after every open. Linux asserts RTS (and DTR) when
  // a tty is opened; the WHOI Micro-Modem 2 garbles its output while RTS
  // is asserted and its own flow control is off (spec §1, §10 quirk 12).
  // A port without modem control lines (a pseudo-terminal) is used as is.
  bool clear_rts = false;
};

class SerialTransport {
 public:
  using DataCallback = std::function<void(std::string_view bytes)>;

  SerialTransport(asio::io_context& context, SerialSettings settings, RetryOptions retry = {});
  ~SerialTransport();
  SerialTransport(const SerialTransport&) = delete;
  SerialTransport& operator=(const SerialTransport&) = delete;

  // Tries to open the port now; on failure reports kWaiting and retries.
  void open(DataCallback on_data, TransportStateCallback on_state);
  // Closes the port; no callback runs after it returns.
  void close();
  // Queues bytes for the device; false (dropped) while the port is not open.
  bool write(std::string_view bytes);

  TransportState state() const;
  const std::string& device() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace acomms::link
