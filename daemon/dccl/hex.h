#pragma once
// Lowercase hex, the form DCCL bytes take in logs, vectors and `acommsctl dccl`.

#include <string>
#include <string_view>

namespace acomms::dccl {

std::string to_hex(std::string_view bytes);
// Accepts upper or lower case; throws std::invalid_argument on an odd length
// or a non-hex character (naming its position).
std::string from_hex(std::string_view hex);

}  // namespace acomms::dccl
