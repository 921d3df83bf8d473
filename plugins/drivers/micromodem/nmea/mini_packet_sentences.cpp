#include "micromodem/nmea/mini_packet_sentences.h"

#include <cstdio>

#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/field_reader.h"
#include "micromodem/nmea/hex.h"

namespace acomms::micromodem {

Sentence to_sentence(const MiniPacket& packet, Talker talker, const char* type) {
  char value[8];
  std::snprintf(value, sizeof value, "%04X", packet.value & 0xFFFFu);
  return Sentence{talker == Talker::kHost ? "CC" : "CA", type,
                  {std::to_string(packet.source), std::to_string(packet.destination), value}};
}

Result<MiniPacket> parse_mini_packet(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCMUC", "CAMUC", "CAMUA"});
  reader.require(3);
  MiniPacket packet;
  packet.source = static_cast<int>(reader.integer(1, "SRC", 0, kMaxAddress));
  packet.destination = static_cast<int>(reader.integer(2, "DEST", 0, kMaxAddress));
  std::string hex = reader.text(3);
  if (reader.ok() && hex.size() != 4) {
    reader.fail(ErrorKind::kBadField, "$" + sentence.address() + " field 3 (HHHH) '" + hex + "' is not 4 hex digits");
  }
  std::string bytes = reader.hex(3, "HHHH");
  if (reader.ok()) {
    packet.value = (static_cast<uint32_t>(static_cast<unsigned char>(bytes[0])) << 8) |
                   static_cast<unsigned char>(bytes[1]);
    if (packet.value > kMaxMiniPacketValue) {
      reader.fail(ErrorKind::kBadField, "$" + sentence.address() + " field 3 (HHHH) '" + hex +
                                            "' is outside 0000..1FFF (13 bits)");
    }
  }
  return reader.finish(packet);
}

}  // namespace acomms::micromodem
