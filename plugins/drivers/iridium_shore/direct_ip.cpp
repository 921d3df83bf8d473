#include "iridium_shore/direct_ip.h"

#include <algorithm>
#include <cstdio>

namespace acomms::drivers::directip {

namespace {

// Big-endian reads from a range already checked to be long enough.
uint16_t get_u16(std::string_view bytes, size_t at) {
  return static_cast<uint16_t>((static_cast<uint8_t>(bytes[at]) << 8) | static_cast<uint8_t>(bytes[at + 1]));
}
uint32_t get_u32(std::string_view bytes, size_t at) {
  return (static_cast<uint32_t>(get_u16(bytes, at)) << 16) | get_u16(bytes, at + 2);
}
void put_u8(std::string& out, uint8_t value) { out.push_back(static_cast<char>(value)); }
void put_u16(std::string& out, uint16_t value) {
  put_u8(out, static_cast<uint8_t>(value >> 8));
  put_u8(out, static_cast<uint8_t>(value & 0xff));
}
void put_u32(std::string& out, uint32_t value) {
  put_u16(out, static_cast<uint16_t>(value >> 16));
  put_u16(out, static_cast<uint16_t>(value & 0xffff));
}

std::string hex_byte(uint8_t value) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02x", value);
  return text;
}

bool is_imei(std::string_view text) {
  return text.size() == kImeiDigits && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// One information element: where its content is in the message.
struct Ie {
  uint8_t iei;
  std::string_view content;
};

// Splits the N bytes after the prefix into IEs, calling `each` per IE in
// order. False with `error` set when an IE does not fit what is left (so
// the IE lengths cannot add up to N).
template <typename Each>
bool for_each_ie(std::string_view body, std::string* error, Each each) {
  size_t at = 0;
  while (at < body.size()) {
    if (body.size() - at < 3) {
      *error = "an IE header at offset " + std::to_string(at + kPrefixBytes) + " is cut off (" +
               std::to_string(body.size() - at) + " bytes are left)";
      return false;
    }
    uint8_t iei = static_cast<uint8_t>(body[at]);
    size_t length = get_u16(body, at + 1);
    if (length > body.size() - at - 3) {
      *error = "IE " + hex_byte(iei) + " claims " + std::to_string(length) + " bytes, " +
               std::to_string(body.size() - at - 3) + " are left";
      return false;
    }
    if (!each(Ie{iei, body.substr(at + 3, length)})) return false;
    at += 3 + length;
  }
  return true;
}

// The N bytes after a checked prefix, or nullopt when the message's size
// is not 3 + N.
std::optional<std::string_view> body_of(std::string_view message, std::string* error) {
  if (message.size() < kPrefixBytes) {
    *error = "message of " + std::to_string(message.size()) + " bytes is shorter than its 3-byte prefix";
    return std::nullopt;
  }
  std::optional<uint16_t> length = parse_prefix(message.substr(0, kPrefixBytes), error);
  if (!length) return std::nullopt;
  if (message.size() - kPrefixBytes != *length) {
    *error = "overall length says " + std::to_string(*length) + " bytes follow, " +
             std::to_string(message.size() - kPrefixBytes) + " do";
    return std::nullopt;
  }
  return message.substr(kPrefixBytes);
}

bool wrong_length(const Ie& ie, size_t expected, const char* name, std::string* error) {
  if (ie.content.size() == expected) return false;
  *error = std::string(name) + " IE " + hex_byte(ie.iei) + " has " + std::to_string(ie.content.size()) +
           " bytes, not " + std::to_string(expected);
  return true;
}

std::optional<MoLocation> parse_location(std::string_view content) {
  if (content.size() != 11) return std::nullopt;
  uint8_t flags = static_cast<uint8_t>(content[0]);
  uint8_t lat_deg = static_cast<uint8_t>(content[1]);
  uint16_t lat_thousandths = get_u16(content, 2);
  uint8_t lon_deg = static_cast<uint8_t>(content[4]);
  uint16_t lon_thousandths = get_u16(content, 5);
  if (lat_deg > 90 || lon_deg > 180 || lat_thousandths > 59999 || lon_thousandths > 59999) return std::nullopt;
  MoLocation location;
  location.latitude_deg = lat_deg + lat_thousandths / 60000.0;
  location.longitude_deg = lon_deg + lon_thousandths / 60000.0;
  if (flags & 0x02) location.latitude_deg = -location.latitude_deg;    // NSI: south
  if (flags & 0x01) location.longitude_deg = -location.longitude_deg;  // EWI: west
  location.cep_km = get_u32(content, 7);
  return location;
}

}  // namespace

std::optional<uint16_t> parse_prefix(std::string_view prefix, std::string* error) {
  if (prefix.size() < kPrefixBytes) {
    *error = "prefix cut off";
    return std::nullopt;
  }
  if (static_cast<uint8_t>(prefix[0]) != kProtocolRevision) {
    *error = "protocol revision " + std::to_string(static_cast<uint8_t>(prefix[0])) + ", expected 1";
    return std::nullopt;
  }
  uint16_t length = get_u16(prefix, 1);
  if (length > kMaxOverallLength) {
    *error = "overall length " + std::to_string(length) + " is above the limit of " +
             std::to_string(kMaxOverallLength);
    return std::nullopt;
  }
  return length;
}

bool mo_session_succeeded(uint8_t session_status) { return session_status <= 2; }

std::optional<MoMessage> parse_mo(std::string_view message, std::string* error) {
  std::optional<std::string_view> body = body_of(message, error);
  if (!body) return std::nullopt;
  MoMessage mo;
  bool have_header = false, have_payload = false;
  bool ok = for_each_ie(*body, error, [&](const Ie& ie) {
    switch (ie.iei) {
      case kMoHeaderIei: {
        if (have_header) return *error = "a second MO header IE", false;
        if (wrong_length(ie, 28, "MO header", error)) return false;
        mo.header.cdr_reference = get_u32(ie.content, 0);
        mo.header.imei = std::string(ie.content.substr(4, kImeiDigits));
        if (!is_imei(mo.header.imei)) return *error = "MO header's IMEI is not 15 ASCII digits", false;
        mo.header.session_status = static_cast<uint8_t>(ie.content[19]);
        mo.header.momsn = get_u16(ie.content, 20);
        mo.header.mtmsn = get_u16(ie.content, 22);
        mo.header.session_time = get_u32(ie.content, 24);
        have_header = true;
        return true;
      }
      case kMoPayloadIei:
        if (have_payload) return *error = "a second MO payload IE", false;
        if (ie.content.size() > kMaxMoPayload) {
          *error = "MO payload of " + std::to_string(ie.content.size()) + " bytes is above the 9602/9603 limit of " +
                   std::to_string(kMaxMoPayload);
          return false;
        }
        mo.payload = std::string(ie.content);
        have_payload = true;
        return true;
      case kMoLocationIei:
        mo.location = parse_location(ie.content);
        if (!mo.location) ++mo.unusable_locations;
        return true;
      default:
        ++mo.unknown_ies;  // skipped by its length (spec §9.1)
        return true;
    }
  });
  if (!ok) return std::nullopt;
  if (!have_header) {
    *error = "no MO header IE (0x01)";
    return std::nullopt;
  }
  return mo;
}

std::string build_mo_confirmation(bool received) {
  std::string out;
  put_u8(out, kProtocolRevision);
  put_u16(out, 4);
  put_u8(out, kMoConfirmationIei);
  put_u16(out, 1);
  put_u8(out, received ? 1 : 0);
  return out;
}

std::string build_mt(const MtSubmission& mt, std::string* error) {
  if (!is_imei(mt.imei)) return *error = "IMEI \"" + mt.imei + "\" is not 15 ASCII digits", "";
  const bool ring = (mt.flags & kSendRingAlert) != 0;
  if ((mt.flags & kAssignMtmsn) && (ring || mt.client_id < 1 || mt.client_id > 65535)) {
    return *error = "assign-MTMSN needs a payload and a client id in 1..65535", "";
  }
  if (ring != mt.payload.empty()) {
    return *error = ring ? "a ring alert carries no payload" : "an MT needs a payload of 1 byte or more", "";
  }
  if (mt.payload.size() > kMaxMtPayload) {
    return *error = "MT payload of " + std::to_string(mt.payload.size()) + " bytes is above the limit of " +
                    std::to_string(kMaxMtPayload), "";
  }
  std::string body;
  put_u8(body, kMtHeaderIei);
  put_u16(body, 21);
  put_u32(body, mt.client_id);
  body += mt.imei;
  put_u16(body, mt.flags);
  if (!ring) {
    put_u8(body, kMtPayloadIei);
    put_u16(body, static_cast<uint16_t>(mt.payload.size()));
    body += mt.payload;
  }
  std::string out;
  put_u8(out, kProtocolRevision);
  put_u16(out, static_cast<uint16_t>(body.size()));
  return out + body;
}

std::optional<MtConfirmation> parse_mt_confirmation(std::string_view message, std::string* error) {
  std::optional<std::string_view> body = body_of(message, error);
  if (!body) return std::nullopt;
  std::optional<MtConfirmation> confirmation;
  bool ok = for_each_ie(*body, error, [&](const Ie& ie) {
    if (ie.iei != kMtConfirmationIei) return true;  // unknown: skipped by its length
    if (confirmation) return *error = "a second MT confirmation IE", false;
    if (wrong_length(ie, 25, "MT confirmation", error)) return false;
    MtConfirmation c;
    c.client_id = get_u32(ie.content, 0);
    c.imei = std::string(ie.content.substr(4, kImeiDigits));
    c.auto_id = get_u32(ie.content, 19);
    c.status = static_cast<int16_t>(get_u16(ie.content, 23));  // signed (spec §9.3.4)
    confirmation = c;
    return true;
  });
  if (!ok) return std::nullopt;
  if (!confirmation) *error = "no MT confirmation IE (0x44)";
  return confirmation;
}

MtOutcome mt_outcome(int16_t status) {
  if (status >= 0) return MtOutcome::kQueued;
  if (status == -5 || status == -6) return MtOutcome::kRetryLater;
  return MtOutcome::kRefused;
}

std::string mt_status_text(int16_t status) {
  static constexpr const char* kRefusals[] = {
      "IMEI malformed",
      "IMEI not provisioned",
      "payload larger than this modem accepts",
      "payload expected, none sent",
      "MT queue full",
      "MT resources unavailable",
      "DirectIP protocol violation",
      "ring alerts disabled for this IMEI",
      "IMEI not attached",
      "source address rejected by the MT filter",
      "MTMSN out of range",
      "client certificate rejected",
  };
  std::string text = std::to_string(status) + " (";
  if (status > 0) {
    text += "queued, position " + std::to_string(status);
  } else if (status == 0) {
    text += "accepted, no payload";
  } else if (status >= -12) {
    text += kRefusals[-status - 1];
  } else {
    text += "unknown refusal";
  }
  return text + ")";
}

}  // namespace acomms::drivers::directip
