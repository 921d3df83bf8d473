#pragma once
// Where a driver meets a fake modem: a pseudo-terminal (what a serial port
// looks like to the driver: open the printed /dev/pts/N like a tty) or a
// TCP port on 127.0.0.1 (what a serial-to-TCP gateway looks like). Either
// carries the modem's byte stream unchanged in both directions.
//
// Output written while no one reads is dropped, as bytes on a serial line
// with nothing attached are: the pty's master is non-blocking and the TCP
// port writes only to a connected client (one at a time; a new connection
// replaces the old, as a gateway's would).

#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/posix/stream_descriptor.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "fake_micromodem.h"

namespace acomms::fake_micromodem {

class PtyPort {
 public:
  PtyPort(asio::io_context& context, FakeMicroModem& modem);
  ~PtyPort();
  const std::string& path() const { return path_; }  // e.g. /dev/pts/7
  uint64_t dropped_bytes() const { return dropped_; }

 private:
  void read();
  void write(std::string_view bytes);
  FakeMicroModem& modem_;
  asio::posix::stream_descriptor master_;
  int slave_ = -1;  // held open so the master never sees a hang-up between clients
  std::string path_;
  std::array<char, 1024> buffer_{};
  uint64_t dropped_ = 0;
};

class TcpPort {
 public:
  // Listens on 127.0.0.1:`port` (0: any free port; see port()).
  TcpPort(asio::io_context& context, FakeMicroModem& modem, uint16_t port);
  uint16_t port() const { return port_; }
  // The gateway goes away (listener and connection closed: the host sees
  // its connection end and new ones refused) and comes back on the same
  // port. The modem behind it keeps running.
  void unplug();
  void plug();

 private:
  void accept();
  void read();
  FakeMicroModem& modem_;
  asio::ip::tcp::acceptor acceptor_;
  uint16_t port_ = 0;
  std::shared_ptr<asio::ip::tcp::socket> client_;
  std::array<char, 1024> buffer_{};
};

}  // namespace acomms::fake_micromodem
