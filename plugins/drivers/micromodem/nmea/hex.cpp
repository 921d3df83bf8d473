#include "micromodem/nmea/hex.h"

namespace acomms::micromodem {
namespace {

int digit_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

}  // namespace

std::string hex_encode(std::string_view bytes) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string hex;
  hex.reserve(bytes.size() * 2);
  for (char c : bytes) {
    auto byte = static_cast<unsigned char>(c);
    hex += kDigits[byte >> 4];
    hex += kDigits[byte & 0xF];
  }
  return hex;
}

Result<std::string> hex_decode(std::string_view hex) {
  if (hex.size() % 2 != 0) {
    return Error{ErrorKind::kBadField,
                 "hex data has an odd number of digits (" + std::to_string(hex.size()) + ")"};
  }
  std::string bytes;
  bytes.reserve(hex.size() / 2);
  for (size_t i = 0; i < hex.size(); i += 2) {
    int high = digit_value(hex[i]);
    int low = digit_value(hex[i + 1]);
    if (high < 0 || low < 0) {
      return Error{ErrorKind::kBadField,
                   "hex data has a non-hex character at digit " + std::to_string(i + (high < 0 ? 1 : 2))};
    }
    bytes += static_cast<char>(high * 16 + low);
  }
  return bytes;
}

}  // namespace acomms::micromodem
