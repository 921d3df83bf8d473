#include "iridium_shore/iridium_shore_settings.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "iridium_shore/direct_ip.h"
#include "link/transmission_rules.h"

namespace acomms::drivers {

namespace {

const std::string kField = "driver.iridium_shore.";

[[noreturn]] void refuse(const std::string& field, const std::string& why) {
  throw std::invalid_argument(kField + field + " " + why);
}

// A non-negative time in seconds; 0 keeps `fallback`.
double seconds_or(double value, double fallback, const std::string& field) {
  if (!std::isfinite(value) || value < 0) refuse(field, "must be 0 (default) or a positive number of seconds");
  return value > 0 ? value : fallback;
}

std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(std::llround(seconds * 1000));
}

}  // namespace

HostAndPort HostAndPort::parse(const std::string& address, const std::string& field, bool allow_port_zero) {
  const auto colon = address.rfind(':');
  auto bad = [&](const std::string& why) {
    return std::invalid_argument(field + " \"" + address + "\" " + why + " (expected host:port)");
  };
  if (colon == std::string::npos || colon == 0) throw bad("has no host");
  HostAndPort out{address.substr(0, colon), address.substr(colon + 1)};
  if (out.host.size() > 2 && out.host.front() == '[' && out.host.back() == ']') {
    out.host = out.host.substr(1, out.host.size() - 2);
  }
  const bool digits = !out.port.empty() && out.port.size() <= 5 &&
                      std::all_of(out.port.begin(), out.port.end(), [](char c) { return c >= '0' && c <= '9'; });
  const int port = digits ? std::stoi(out.port) : -1;
  if (port < (allow_port_zero ? 0 : 1) || port > 65535) throw bad("has no valid port");
  return out;
}

IridiumShoreSettings IridiumShoreSettings::from_config(const v1::DriverConfig& config) {
  const auto& shore = config.iridium_shore();
  IridiumShoreSettings s;
  s.own_id = link::own_modem_id(config);
  if (shore.mo_listen().empty()) refuse("mo_listen", "is empty: the MO server needs a host:port to listen on");
  s.mo_listen = HostAndPort::parse(shore.mo_listen(), kField + "mo_listen", /*allow_port_zero=*/true);
  s.mo_listen_text = shore.mo_listen();
  if (!shore.mt_gateway().empty()) {
    s.mt_gateway_address = HostAndPort::parse(shore.mt_gateway(), kField + "mt_gateway");
  }
  s.mt_gateway = shore.mt_gateway();
  for (int i = 0; i < shore.modems_size(); ++i) {
    const auto& modem = shore.modems(i);
    const std::string field = "modems[" + std::to_string(i) + "]";
    const std::string& imei = modem.imei();
    if (imei.size() != directip::kImeiDigits ||
        !std::all_of(imei.begin(), imei.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      refuse(field + ".imei", "\"" + imei + "\" is not 15 digits");
    }
    if (modem.modem_id() == 0 || static_cast<int32_t>(modem.modem_id()) == s.own_id) {
      refuse(field + ".modem_id", "must be a vehicle's id: not 0 (broadcast) and not this node's own id");
    }
    auto id = static_cast<int32_t>(modem.modem_id());
    if (!s.modem_id_by_imei.emplace(imei, id).second) refuse(field + ".imei", imei + " is listed twice");
    if (!s.imei_by_modem_id.emplace(id, imei).second) {
      refuse(field + ".modem_id", std::to_string(id) + " is given to two IMEIs");
    }
  }
  if (shore.max_mo_connections() > 0) s.max_mo_connections = shore.max_mo_connections();
  s.mo_read_timeout = millis(seconds_or(shore.mo_read_timeout_s(), 10, "mo_read_timeout_s"));
  s.mo_confirmation = shore.mo_confirmation();
  s.mo_dedup_window_s = seconds_or(shore.mo_dedup_window_s(), 86400, "mo_dedup_window_s");
  if (shore.mo_dedup_capacity() > 0) s.mo_dedup_capacity = shore.mo_dedup_capacity();
  s.mt_connect_timeout = millis(seconds_or(shore.mt_connect_timeout_s(), 10, "mt_connect_timeout_s"));
  s.mt_confirmation_timeout = millis(seconds_or(shore.mt_confirmation_timeout_s(), 10, "mt_confirmation_timeout_s"));
  s.mt_check_interval_s = seconds_or(shore.mt_check_interval_s(), 5, "mt_check_interval_s");
  if (shore.mt_max_bytes() > directip::kMaxMtPayload) {
    refuse("mt_max_bytes", "is " + std::to_string(shore.mt_max_bytes()) + ", above the 9602/9603 MT limit of 270");
  }
  if (shore.mt_max_bytes() > 0) s.mt_max_bytes = shore.mt_max_bytes();
  s.mt_retry_min_s = seconds_or(shore.mt_retry_min_s(), 30, "mt_retry_min_s");
  s.mt_retry_max_s = std::max(s.mt_retry_min_s, seconds_or(shore.mt_retry_max_s(), 600, "mt_retry_max_s"));
  s.mt_refused_wait_s = seconds_or(shore.mt_refused_wait_s(), 3600, "mt_refused_wait_s");
  return s;
}

}  // namespace acomms::drivers
