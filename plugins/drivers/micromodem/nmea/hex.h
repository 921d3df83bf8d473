#pragma once
// Frame payloads travel as hexadecimal in $CCTXD / $CARXD (spec §2.3 rule 7):
// sent upper-case; received in either case (real MM2 lines use lower case).

#include <string>
#include <string_view>

#include "micromodem/nmea/result.h"

namespace acomms::micromodem {

std::string hex_encode(std::string_view bytes);
// Refuses an odd number of digits or a non-hex character (kBadField).
Result<std::string> hex_decode(std::string_view hex);

}  // namespace acomms::micromodem
