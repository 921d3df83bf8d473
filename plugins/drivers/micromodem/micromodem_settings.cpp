// Reading driver.micromodem: defaults for what is unset (0), and the checks
// in the order the driver has always made them, so that a config with
// several mistakes still names the same one first.
#include "micromodem/micromodem_settings.h"

#include <stdexcept>
#include <string>

#include "link/transmission_rules.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;

MicroModemSettings read_micromodem_settings(const v1::DriverConfig& config) {
  const auto& micromodem = config.micromodem();
  MicroModemSettings settings;
  settings.id = link::own_modem_id(config);
  for (const std::string& entry : micromodem.cfg()) settings.user_cfg.push_back(parse_cfg_entry(entry));
  if (micromodem.time_scale() < 0) {
    throw std::invalid_argument("driver.micromodem.time_scale must be > 0 (0: real time)");
  }
  if (micromodem.time_scale() != 0) settings.time_scale = micromodem.time_scale();
  if (!(micromodem.command_timeout_s() <= 0)) {
    settings.command_timeout =
        std::chrono::duration_cast<Duration>(std::chrono::duration<double>(micromodem.command_timeout_s()));
  }
  settings.fdp_data = micromodem.fdp_data();

  if (micromodem.max_range_m() > 0) settings.cycle.max_range_m = micromodem.max_range_m();
  settings.cycle.time_scale = settings.time_scale;

  DriverSpecificExchange::Settings& exchange = settings.exchange;
  exchange.own_id = settings.id;
  exchange.time_scale = settings.time_scale;
  double c = micromodem.sound_speed_mps();
  if (c < 0 || (c > 0 && (c < 1000 || c > 2000))) {
    throw std::invalid_argument("driver.micromodem.sound_speed_mps " + std::to_string(c) +
                                " is outside 1000..2000 m/s (0: 1500)");
  }
  if (c > 0) exchange.sound_speed = c;
  if (micromodem.max_range_m() > 0) exchange.max_range_m = micromodem.max_range_m();
  for (const ConfigParameter& p : settings.user_cfg) {
    if (p.name == "psk.packet.mod_hdr_version") exchange.fdp_configured = p.value == "1";
  }
  for (uint32_t mm1 : micromodem.mm1_modems()) {
    if (mm1 < 1 || mm1 > static_cast<uint32_t>(nmea::kMaxAddress)) {
      throw std::invalid_argument("driver.micromodem.mm1_modems " + std::to_string(mm1) + " is not a modem id (1..127)");
    }
    exchange.mm1_modems.push_back(static_cast<int32_t>(mm1));
  }

  if (settings.fdp_data && !exchange.fdp_configured) {
    throw std::invalid_argument(
        "driver.micromodem.fdp_data needs cfg: \"psk.packet.mod_hdr_version,1\" (FDP packets; on every modem of "
        "the network)");
  }
  if (settings.id > nmea::kMaxAddress) {
    throw std::invalid_argument("driver.modem_id " + std::to_string(settings.id) +
                                " is not a Micro-Modem address (1..127)");
  }
  return settings;
}

}  // namespace acomms::drivers::micromodem
