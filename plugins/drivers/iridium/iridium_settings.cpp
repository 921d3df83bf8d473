#include "iridium/iridium_settings.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "iridium/at/sbd_binary.h"
#include "link/transmission_rules.h"

namespace acomms::drivers::iridium {
namespace {

Duration seconds_or(double value, double fallback, const char* field) {
  if (value < 0 || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("driver.iridium.") + field + " is " + std::to_string(value) +
                                ": must be a positive number of seconds (0: " + std::to_string(fallback) + ")");
  }
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(value == 0 ? fallback : value));
}

}  // namespace

IridiumSettings IridiumSettings::from_config(const v1::DriverConfig& config) {
  const auto& c = config.iridium();
  IridiumSettings s;
  s.id = link::own_modem_id(config);
  if (c.shore_id() == 0) {
    throw std::invalid_argument("driver.iridium.shore_id is unset: give the modem id of the shore node (> 0)");
  }
  if (c.shore_id() == static_cast<uint32_t>(s.id)) {
    throw std::invalid_argument("driver.iridium.shore_id is this node's own modem_id " + std::to_string(s.id));
  }
  s.shore_id = static_cast<int32_t>(c.shore_id());
  if (!c.imei().empty() &&
      (c.imei().size() != 15 || !std::all_of(c.imei().begin(), c.imei().end(), [](char ch) { return ch >= '0' && ch <= '9'; }))) {
    throw std::invalid_argument("driver.iridium.imei \"" + c.imei() + "\" is not 15 digits");
  }
  s.imei = c.imei();
  s.rts_cts = c.rts_cts();
  if (c.max_mo_bytes() > ::acomms::iridium::kMaxMoBytes) {
    throw std::invalid_argument("driver.iridium.max_mo_bytes is " + std::to_string(c.max_mo_bytes()) +
                                ": a 9602/9603 takes at most 340 bytes per MO");
  }
  s.max_mo_bytes = c.max_mo_bytes() == 0 ? ::acomms::iridium::kMaxMoBytes : c.max_mo_bytes();
  s.mailbox_check = seconds_or(c.mailbox_check_s(), 300, "mailbox_check_s");
  s.send_check = seconds_or(c.send_check_s(), 10, "send_check_s");
  s.session_timeout = seconds_or(c.session_timeout_s(), 90, "session_timeout_s");
  s.command_timeout = seconds_or(c.command_timeout_s(), 5, "command_timeout_s");
  return s;
}

}  // namespace acomms::drivers::iridium
