#pragma once
// driver.micromodem (api/proto/acomms/drivers/micromodem.proto),
// read and checked once, into what each part of the driver is built from.
//
// The problem: the driver's parts each need a few of the same settings
// (the time scale divides every wait; the range bounds both the data
// cycle's ACK wait and a ping's), and a bad value must stop the driver
// before it opens the port, with an error naming the field. The decision:
// one function reads the config in full and hands out finished settings,
// so the driver's constructor only builds, and no setting is read twice.
//
// Threads: a value (any thread).

#include <chrono>
#include <cstdint>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "micromodem/data_cycle.h"
#include "micromodem/driver_specific_exchange.h"
#include "micromodem/startup_sequence.h"

namespace acomms::drivers::micromodem {

struct MicroModemSettings {
  int32_t id = 1;                         // driver.modem_id: the modem's SRC
  std::vector<ConfigParameter> user_cfg;  // driver.micromodem.cfg, applied at every start-up
  double time_scale = 1;                  // the modem runs this much faster (the fake, in tests)
  // How long a command waits for its echo, in modem time (before the scale).
  Duration command_timeout = std::chrono::seconds(5);
  bool fdp_data = false;  // DATA and ACKs as FDP packets (MM2)
  CycleTimeouts cycle;
  DriverSpecificExchange::Settings exchange;  // also: the MM1 modems FDP DATA must not go to
};

// Throws std::invalid_argument naming the field: a cfg entry that is not
// "KEY,VALUE", a negative time_scale, a sound speed outside 1000..2000 m/s,
// an mm1_modems entry that is no modem id, fdp_data without the FDP header
// setting in cfg, or a modem_id above 127.
MicroModemSettings read_micromodem_settings(const v1::DriverConfig& config);

}  // namespace acomms::drivers::micromodem
