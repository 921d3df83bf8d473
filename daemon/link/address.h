#pragma once
// "host:port" as written in the config ("127.0.0.1:50100", "[::1]:50100",
// "modem-gw:4001").

#include <string>

namespace acomms::link {

struct HostPort {
  std::string host;
  std::string port;
};

// Splits `address`; throws std::invalid_argument naming `field` and the
// address when it has no host or no port, or the port is not 1..65535
// (0 too, "any free port", when allow_port_zero: for a listening socket).
HostPort parse_host_port(const std::string& address, const std::string& field,
                         bool allow_port_zero = false);

}  // namespace acomms::link
