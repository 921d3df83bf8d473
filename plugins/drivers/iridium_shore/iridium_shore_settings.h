#pragma once
// The "iridium_shore" driver's settings with their defaults applied and
// checked once, at construction, so that a bad config stops the daemon at
// start with the field named (not at the first MO, hours later).
//
// Thread-safe: an immutable value once built.

#include <chrono>
#include <cstdint>
#include <map>
#include <string>

#include "acomms/v1/config.pb.h"

namespace acomms::drivers {

// "host:port" split at its last colon ("[::1]:10800" keeps its brackets
// off the host). Throws std::invalid_argument naming `field` when there is
// no host, or the port is not 1..65535 (or 0, "any", when allow_port_zero).
struct HostAndPort {
  std::string host;
  std::string port;
  static HostAndPort parse(const std::string& address, const std::string& field, bool allow_port_zero = false);
};

struct IridiumShoreSettings {
  int32_t own_id = 1;
  HostAndPort mo_listen;
  std::string mo_listen_text;
  std::string mt_gateway;  // "": no MTs
  HostAndPort mt_gateway_address;
  std::map<std::string, int32_t> modem_id_by_imei;
  std::map<int32_t, std::string> imei_by_modem_id;
  uint32_t max_mo_connections = 16;
  std::chrono::milliseconds mo_read_timeout{10'000};
  bool mo_confirmation = false;
  double mo_dedup_window_s = 86400;
  uint32_t mo_dedup_capacity = 100000;
  std::chrono::milliseconds mt_connect_timeout{10'000};
  std::chrono::milliseconds mt_confirmation_timeout{10'000};
  double mt_check_interval_s = 5;
  uint32_t mt_max_bytes = 270;
  double mt_retry_min_s = 30;
  double mt_retry_max_s = 600;
  double mt_refused_wait_s = 3600;

  // Throws std::invalid_argument naming the field (driver.iridium_shore.X)
  // and the bound it broke.
  static IridiumShoreSettings from_config(const v1::DriverConfig& config);
};

}  // namespace acomms::drivers
