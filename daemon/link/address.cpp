#include "link/address.h"

#include <stdexcept>

namespace acomms::link {

HostPort parse_host_port(const std::string& address, const std::string& field, bool allow_port_zero) {
  auto bad = [&](const std::string& why) {
    return std::invalid_argument(field + ": \"" + address + "\" " + why + " (expected host:port)");
  };
  HostPort out;
  size_t colon = address.rfind(':');
  if (colon == std::string::npos) throw bad("has no port");
  out.host = address.substr(0, colon);
  out.port = address.substr(colon + 1);
  // IPv6 literals are bracketed so that their colons are not the port's.
  if (out.host.size() >= 2 && out.host.front() == '[' && out.host.back() == ']') {
    out.host = out.host.substr(1, out.host.size() - 2);
  } else if (out.host.find(':') != std::string::npos) {
    throw bad("is ambiguous: bracket IPv6 addresses");
  }
  if (out.host.empty()) throw bad("has no host");
  if (out.port.empty() || out.port.size() > 5 ||
      out.port.find_first_not_of("0123456789") != std::string::npos) {
    throw bad("has no valid port");
  }
  int port = std::stoi(out.port);
  if (port < (allow_port_zero ? 0 : 1) || port > 65535) throw bad("has a port outside 1..65535");
  return out;
}

}  // namespace acomms::link
