#pragma once
// Hexadecimal bytes: DCCL bytes in logs, test vectors and `acommsctl dccl`
// (lower case), and a Micro-Modem's frame payloads and NMEA checksums
// (upper case on the wire, either case accepted when received).
//
// Two copies of the digit table and the decoding loop existed, one per user.
// The decoding here reports what is wrong (odd length, or the position of the
// first non-hex character) and leaves the wording to the caller, because
// each caller's error is already part of what its users read: a thrown
// std::invalid_argument for dccl, a kBadField result for the modem.
//
// Thread-safe: pure functions.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::util {

enum class HexCase { kLower, kUpper };

// The value of one hex digit (either case), or -1 if c is not one.
inline int hex_digit_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Two digits per byte, high nibble first.
inline std::string hex_encode(std::string_view bytes, HexCase letters = HexCase::kLower) {
  const char* digits = letters == HexCase::kLower ? "0123456789abcdef" : "0123456789ABCDEF";
  std::string hex;
  hex.reserve(bytes.size() * 2);
  for (char c : bytes) {
    auto byte = static_cast<unsigned char>(c);
    hex += digits[byte >> 4];
    hex += digits[byte & 0xf];
  }
  return hex;
}

// Why a string did not decode: an odd number of digits (checked first), or
// else the 1-based position of its first non-hex character.
struct HexError {
  bool odd_length = false;
  size_t position = 0;
};

// The bytes that `hex` spells (either case), or nullopt with *error filled.
inline std::optional<std::string> hex_decode(std::string_view hex, HexError* error) {
  if (hex.size() % 2 != 0) {
    *error = HexError{true, 0};
    return std::nullopt;
  }
  std::string bytes(hex.size() / 2, '\0');
  for (size_t i = 0; i < hex.size(); i += 2) {
    int high = hex_digit_value(hex[i]);
    int low = hex_digit_value(hex[i + 1]);
    if (high < 0 || low < 0) {
      *error = HexError{false, (high < 0 ? i : i + 1) + 1};
      return std::nullopt;
    }
    bytes[i / 2] = static_cast<char>(high << 4 | low);
  }
  return bytes;
}

}  // namespace acomms::util
