#include "micromodem/nmea/hex.h"

#include "util/hex.h"

namespace acomms::micromodem {

std::string hex_encode(std::string_view bytes) { return util::hex_encode(bytes, util::HexCase::kUpper); }

Result<std::string> hex_decode(std::string_view hex) {
  util::HexError error;
  std::optional<std::string> bytes = util::hex_decode(hex, &error);
  if (bytes) return *std::move(bytes);
  if (error.odd_length) {
    return Error{ErrorKind::kBadField,
                 "hex data has an odd number of digits (" + std::to_string(hex.size()) + ")"};
  }
  return Error{ErrorKind::kBadField, "hex data has a non-hex character at digit " + std::to_string(error.position)};
}

}  // namespace acomms::micromodem
