#pragma once
// The fake_micromodem executable's commands about the line between a modem
// and its host, beside fault_console.h's faults of the modem itself. They
// need the process's ports and real time, which the modem library has not:
//   <address> unplug                       the TCP port goes away (as a
//                                          serial-to-TCP gateway that reboots)
//   <address> plug                         and comes back on the same port
//   <address> noise-for <seconds> [bytes/s]  random bytes on the line for
//                                          that long (real seconds), in
//                                          20 chunks a second; default 1920
//                                          bytes/s, a 19200 baud 8N1 line
//                                          full (spec §1)
// The modem's own lines still go out during noise, between its chunks.

#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "fake_micromodem.h"
#include "host_ports.h"

namespace acomms::fake_micromodem {

class LineConsole {
 public:
  LineConsole(asio::io_context& context, std::map<int, FakeMicroModem*> modems, std::map<int, TcpPort*> tcp_ports);

  // "ok" or what was wrong; nullopt when `line` is not one of these commands.
  std::optional<std::string> run(const std::string& line);

 private:
  void noise(FakeMicroModem& modem, std::chrono::steady_clock::time_point until, size_t chunk,
             std::shared_ptr<asio::steady_timer> timer);

  asio::io_context& context_;
  std::map<int, FakeMicroModem*> modems_;
  std::map<int, TcpPort*> tcp_ports_;
};

}  // namespace acomms::fake_micromodem
