#pragma once
// The 13-bit user mini-packet (spec §7.4): $CCMUC sends, $CAMUC echoes,
// $CAMUA reports one received (DEST 0 reaches everyone). The value is 4
// hex digits, 0x0000-0x1FFF: the top 3 bits of the 16 must be 0.

#include <cstdint>

#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

inline constexpr uint32_t kMaxMiniPacketValue = 0x1FFF;

struct MiniPacket {
  int source = 0;
  int destination = 0;
  uint32_t value = 0;
  bool operator==(const MiniPacket&) const = default;
};
// `type` is "MUC" (command, echo) or "MUA" (received).
Sentence to_sentence(const MiniPacket& packet, Talker talker, const char* type = "MUC");
Result<MiniPacket> parse_mini_packet(const Sentence& sentence);  // CCMUC, CAMUC, CAMUA

}  // namespace acomms::micromodem
