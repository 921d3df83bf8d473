// Receipts' bytes (layout and reasons in receipt.h).
#include "route/receipt.h"

#include "route/envelope.h"
#include "util/little_endian.h"

namespace acomms::route {

std::string encode_receipt(const Receipt& receipt, uint32_t envelope_id) {
  std::string out;
  out.reserve(kReceiptBytes);
  util::put_le(&out, static_cast<uint16_t>((envelope_id << 1) | 1), 2);
  util::put_le(&out, static_cast<uint8_t>(receipt.kind), 1);
  util::put_le(&out, receipt.seq, 2);
  return out;
}

std::optional<Receipt> decode_receipt(std::string_view payload, uint32_t envelope_id) {
  if (payload.size() != kReceiptBytes || !starts_envelope(payload, envelope_id)) return std::nullopt;
  const auto* bytes = reinterpret_cast<const unsigned char*>(payload.data());
  const uint8_t kind = bytes[2];
  if (kind != static_cast<uint8_t>(ReceiptKind::kDelivered) && kind != static_cast<uint8_t>(ReceiptKind::kExpired)) {
    return std::nullopt;
  }
  Receipt receipt;
  receipt.kind = static_cast<ReceiptKind>(kind);
  receipt.seq = static_cast<uint16_t>(util::load_le(bytes + 3, 2));
  return receipt;
}

const char* to_string(ReceiptKind kind) {
  switch (kind) {
    case ReceiptKind::kDelivered: return "delivered";
    case ReceiptKind::kExpired: return "expired";
  }
  return "?";
}

}  // namespace acomms::route
