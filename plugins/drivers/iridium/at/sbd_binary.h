#pragma once
// The binary blocks of the SBD AT interface (spec §4.1, §4.3): what the host
// writes after `READY` for AT+SBDWB, and the checksum both directions use.
//
// The checksum is the sum of the payload bytes as unsigned integers, kept
// to its low 16 bits and sent high byte first. It is the only integrity
// check on the serial side, so both the writer and the reader use this one
// function; the fake modem (tests/fakes/iridium) computes its own, so a
// mistake here cannot hide behind a shared copy.
//
// Thread-safe: pure functions.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace acomms::iridium {

// The 9602/9603 limits (spec §6.1).
inline constexpr size_t kMaxMoBytes = 340;
inline constexpr size_t kMaxMtBytes = 270;

// Sum of the bytes, low 16 bits ("hello" -> 0x0214).
uint16_t sbd_checksum(std::string_view payload);

// "AT+SBDWB=<n>\r": n is the payload length without the checksum.
std::string sbdwb_command(size_t payload_bytes);

// What follows READY: the payload, then its checksum high byte first,
// nothing else (no CR). The payload must be 1..kMaxMoBytes bytes (the
// caller checks; the modem answers 3 otherwise).
std::string sbdwb_block(std::string_view payload);

}  // namespace acomms::iridium
