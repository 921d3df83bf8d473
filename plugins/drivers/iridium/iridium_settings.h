#pragma once
// driver.iridium (api/proto/acomms/drivers/iridium.proto), read and checked
// once, with the defaults filled in: the rest of the driver reads plain
// values and never a zero meaning "default".
//
// Thread-safe: a value.

#include <chrono>
#include <cstdint>
#include <string>

#include "acomms/v1/config.pb.h"

namespace acomms::drivers::iridium {

using Duration = std::chrono::system_clock::duration;

struct IridiumSettings {
  int32_t id = 1;        // driver.modem_id (0: 1)
  int32_t shore_id = 0;  // where MOs go, whom MTs come from
  std::string imei;      // expected; empty: any
  bool rts_cts = false;
  uint32_t max_mo_bytes = 340;
  Duration mailbox_check{std::chrono::seconds(300)};
  Duration send_check{std::chrono::seconds(10)};
  Duration session_timeout{std::chrono::seconds(90)};
  Duration command_timeout{std::chrono::seconds(5)};

  // Throws std::invalid_argument naming the field and its bound.
  static IridiumSettings from_config(const v1::DriverConfig& config);
};

}  // namespace acomms::drivers::iridium
