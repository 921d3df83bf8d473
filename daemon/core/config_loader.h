#pragma once
// Loading acommsd's config: protobuf text format against acomms.v1.Config,
// then checks the parser cannot make (address syntax, name syntax), each
// reported as a ConfigError with the file, line, column and field.
//
// Thread-safe: functions of their input only; nothing is kept between calls.

#include <string>
#include <string_view>

#include "acomms/v1/config.pb.h"

namespace acomms::core {

inline constexpr std::string_view kDefaultDataDir = "/var/lib/acommsd";
inline constexpr std::string_view kDefaultUnixSocket = "/run/acommsd/acommsd.sock";
inline constexpr std::string_view kDefaultDriver = "sim";
// No medium access until a cycle is configured: a node never transmits
// into a network whose schedule it does not know.
inline constexpr std::string_view kDefaultMac = "none";

// Parses `text` (named `file_name` in errors), validates it and fills in
// defaults. Throws ConfigError.
v1::Config parse_config(std::string_view text, const std::string& file_name);

// Reads and parses the file at `path`. Throws ConfigError (also when the file
// cannot be read).
v1::Config load_config_file(const std::string& path);

// A complete config with every setting explained, as printed by
// `acommsd --example-config`. It parses to the defaults.
std::string_view example_config();

// Checks the settings that command-line overrides can also change. Throws
// std::invalid_argument naming the setting.
void check_effective_config(const v1::Config& config);

}  // namespace acomms::core
