// The consistency announce's bytes (layout and reasons in consistency_announce.h).
#include "node/consistency_announce.h"

#include <stdexcept>

#include "util/little_endian.h"

namespace acomms::node {
namespace {

bool valid_id(uint32_t announce_id) { return announce_id >= 128 && announce_id <= 32767; }

uint16_t id_header(uint32_t announce_id) { return static_cast<uint16_t>((announce_id << 1) | 1); }

}  // namespace

std::string encode_announce(uint32_t digest, uint32_t announce_id) {
  if (!valid_id(announce_id)) {
    throw std::invalid_argument("consistency.announce_id " + std::to_string(announce_id) + " is not in 128..32767");
  }
  std::string out;
  out.reserve(kAnnounceBytes);
  util::put_le(&out, id_header(announce_id), 2);
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((digest >> shift) & 0xff));
  return out;
}

bool starts_announce(std::string_view bytes, uint32_t announce_id) {
  if (bytes.size() < 2 || !valid_id(announce_id)) return false;
  return util::load_le(reinterpret_cast<const unsigned char*>(bytes.data()), 2) == id_header(announce_id);
}

std::optional<uint32_t> decode_announce(std::string_view bytes, uint32_t announce_id, std::string* error) {
  auto refuse = [&](std::string why) -> std::optional<uint32_t> {
    if (error != nullptr) *error = std::move(why);
    return std::nullopt;
  };
  if (!valid_id(announce_id)) return refuse("announce id out of range");
  if (!starts_announce(bytes, announce_id)) return refuse("not an announce (DCCL id differs)");
  if (bytes.size() < kAnnounceBytes) {
    return refuse("announce truncated: " + std::to_string(bytes.size()) + " bytes of " +
                  std::to_string(kAnnounceBytes));
  }
  uint32_t digest = 0;
  for (size_t i = 2; i < kAnnounceBytes; ++i) digest = (digest << 8) | static_cast<unsigned char>(bytes[i]);
  return digest;
}

}  // namespace acomms::node
