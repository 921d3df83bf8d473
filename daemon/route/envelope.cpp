// The routing envelope's bytes (layout and reasons in envelope.h).
#include "route/envelope.h"

#include <cmath>
#include <stdexcept>

#include "util/little_endian.h"

namespace acomms::route {
namespace {

void check_envelope_id(uint32_t envelope_id) {
  // Two-byte ids only: a one-byte id (0-127) is the common choice for user
  // types, and the envelope must not take one from them.
  if (envelope_id < 128 || envelope_id > 32767) {
    throw std::invalid_argument("routing.envelope_id " + std::to_string(envelope_id) + " is not in 128..32767");
  }
}

uint16_t id_header(uint32_t envelope_id) { return static_cast<uint16_t>((envelope_id << 1) | 1); }

}  // namespace

std::string encode_envelope(const Envelope& e, uint32_t envelope_id) {
  check_envelope_id(envelope_id);
  if (e.payload.empty() || e.payload.size() > kMaxPayloadBytes) {
    throw std::invalid_argument("envelope payload of " + std::to_string(e.payload.size()) +
                                " bytes: must be 1.." + std::to_string(kMaxPayloadBytes));
  }
  if (e.destination == 0) throw std::invalid_argument("envelope destination 0 (broadcast) is not routed");
  if (e.hop_limit == 0 || e.hop_limit > kMaxHopLimit) {
    throw std::invalid_argument("envelope hop_limit " + std::to_string(e.hop_limit) + " is not in 1..15");
  }
  if (e.hops > e.hop_limit) {
    throw std::invalid_argument("envelope hops " + std::to_string(e.hops) + " above its hop_limit " +
                                std::to_string(e.hop_limit));
  }
  std::string out;
  out.reserve(kEnvelopeOverheadBytes + e.payload.size());
  util::put_le(&out, id_header(envelope_id), 2);
  util::put_le(&out, uint64_t{e.hops} | (uint64_t{e.hop_limit} << 4), 1);
  util::put_le(&out, e.origin, 2);
  util::put_le(&out, e.destination, 2);
  util::put_le(&out, e.seq, 2);
  util::put_le(&out, e.ttl_s, 2);
  util::put_le(&out, e.value_tenths, 1);
  util::put_le(&out, e.payload.size(), 1);
  out += e.payload;
  return out;
}

bool starts_envelope(std::string_view bytes, uint32_t envelope_id) {
  if (bytes.size() < 2) return false;
  return util::load_le(reinterpret_cast<const unsigned char*>(bytes.data()), 2) == id_header(envelope_id);
}

std::optional<Envelope> decode_envelope(std::string_view bytes, uint32_t envelope_id, size_t* used,
                                        std::string* error) {
  auto refuse = [&](std::string why) -> std::optional<Envelope> {
    if (error != nullptr) *error = std::move(why);
    return std::nullopt;
  };
  if (envelope_id < 128 || envelope_id > 32767) return refuse("envelope id out of range");
  if (!starts_envelope(bytes, envelope_id)) return refuse("not an envelope (DCCL id differs)");
  if (bytes.size() < kEnvelopeOverheadBytes) {
    return refuse("envelope truncated: " + std::to_string(bytes.size()) + " bytes, head needs " +
                  std::to_string(kEnvelopeOverheadBytes));
  }
  std::string_view in = bytes.substr(2);
  uint64_t hops = 0, origin = 0, dest = 0, seq = 0, ttl = 0, value = 0, length = 0;
  // The head's length was checked: these takes cannot fail.
  util::take_le(&in, 1, &hops);
  util::take_le(&in, 2, &origin);
  util::take_le(&in, 2, &dest);
  util::take_le(&in, 2, &seq);
  util::take_le(&in, 2, &ttl);
  util::take_le(&in, 1, &value);
  util::take_le(&in, 1, &length);
  Envelope e;
  e.hops = static_cast<uint8_t>(hops & 0x0f);
  e.hop_limit = static_cast<uint8_t>(hops >> 4);
  if (e.hop_limit == 0) return refuse("envelope hop limit 0");
  if (e.hops > e.hop_limit) return refuse("envelope hops above its limit");
  if (dest == 0) return refuse("envelope destination 0 (broadcast is not routed)");
  if (length == 0) return refuse("envelope with an empty message");
  if (in.size() < length) {
    return refuse("envelope truncated: message of " + std::to_string(length) + " bytes, " +
                  std::to_string(in.size()) + " left");
  }
  e.origin = static_cast<uint16_t>(origin);
  e.destination = static_cast<uint16_t>(dest);
  e.seq = static_cast<uint16_t>(seq);
  e.ttl_s = static_cast<uint16_t>(ttl);
  e.value_tenths = static_cast<uint8_t>(value);
  e.payload.assign(in.substr(0, length));
  if (used != nullptr) *used = kEnvelopeOverheadBytes + length;
  return e;
}

uint8_t value_to_tenths(double value_base) {
  if (!(value_base > 0)) return 0;
  double tenths = std::round(value_base * 10);
  return tenths >= 255 ? 255 : static_cast<uint8_t>(tenths);
}

uint16_t ttl_to_seconds(double ttl_s) {
  if (!(ttl_s > 0)) return 0;
  return ttl_s >= kMaxTtlSeconds ? static_cast<uint16_t>(kMaxTtlSeconds) : static_cast<uint16_t>(std::floor(ttl_s));
}

}  // namespace acomms::route
