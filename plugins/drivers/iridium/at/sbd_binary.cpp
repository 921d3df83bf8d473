#include "iridium/at/sbd_binary.h"

namespace acomms::iridium {

uint16_t sbd_checksum(std::string_view payload) {
  uint32_t sum = 0;
  for (char c : payload) sum += static_cast<unsigned char>(c);
  return static_cast<uint16_t>(sum & 0xFFFF);
}

std::string sbdwb_command(size_t payload_bytes) { return "AT+SBDWB=" + std::to_string(payload_bytes) + "\r"; }

std::string sbdwb_block(std::string_view payload) {
  std::string block(payload);
  const uint16_t sum = sbd_checksum(payload);
  block.push_back(static_cast<char>(sum >> 8));
  block.push_back(static_cast<char>(sum & 0xFF));
  return block;
}

}  // namespace acomms::iridium
