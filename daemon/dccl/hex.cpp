#include "dccl/hex.h"

#include <stdexcept>

#include "util/hex.h"

namespace acomms::dccl {

std::string to_hex(std::string_view bytes) { return util::hex_encode(bytes, util::HexCase::kLower); }

std::string from_hex(std::string_view hex) {
  util::HexError error;
  std::optional<std::string> bytes = util::hex_decode(hex, &error);
  if (bytes) return *std::move(bytes);
  if (error.odd_length) throw std::invalid_argument("odd number of hex digits");
  throw std::invalid_argument("not a hex digit at position " + std::to_string(error.position) + ": '" +
                              std::string(1, hex[error.position - 1]) + "'");
}

}  // namespace acomms::dccl
