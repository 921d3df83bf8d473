#pragma once
// The vehicle's Iridium driver block of an acommsd config, pointed at the
// fake 9603 a test hosts over TCP (tests/fakes/iridium/tcp_modem_host.h).
//
// Written once for the tests that run a real vehicle daemon on the fake
// modem (iridium_vehicle_test, iridium_end_to_end_test): the port form,
// the IMEI check and the fast driver restarts are the same; the session
// timings (`settings`, inside iridium { }) are each test's own.
//
// Thread-safe: a pure function.

#include <string>

namespace acomms::testing {

// `driver { name: "iridium" ... }` for modem `modem_id`, the fake on
// 127.0.0.1:`port`, the shore node `shore_id`, the fake's `imei`.
inline std::string iridium_vehicle_driver(int modem_id, int port, int shore_id, const std::string& imei,
                                          const std::string& settings) {
  return "driver { name: \"iridium\" modem_id: " + std::to_string(modem_id) +
         " restart_min_s: 0.5 restart_max_s: 2\n  iridium { port: \"tcp:127.0.0.1:" + std::to_string(port) +
         "\" shore_id: " + std::to_string(shore_id) + " imei: \"" + imei + "\" " + settings + " } }\n";
}

}  // namespace acomms::testing
