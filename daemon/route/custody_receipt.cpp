// Custody receipts' bytes (layout and reasons in custody_receipt.h).
#include "route/custody_receipt.h"

#include "util/little_endian.h"

namespace acomms::route {

namespace {

bool is_verdict(uint8_t byte) {
  return byte == static_cast<uint8_t>(CustodyVerdict::kTaken) || byte == static_cast<uint8_t>(CustodyVerdict::kRefused);
}

}  // namespace

std::string encode_custody_receipt(const CustodyReceipt& receipt, uint32_t envelope_id) {
  std::string out;
  out.reserve(kCustodyReceiptBytes);
  util::put_le(&out, static_cast<uint16_t>((envelope_id << 1) | 1), 2);
  util::put_le(&out, static_cast<uint8_t>(receipt.verdict), 1);
  util::put_le(&out, receipt.about.origin, 2);
  util::put_le(&out, receipt.about.seq, 2);
  return out;
}

bool starts_custody_receipt(std::string_view bytes, uint32_t envelope_id) {
  return bytes.size() >= 3 && starts_envelope(bytes, envelope_id) && is_verdict(static_cast<uint8_t>(bytes[2]));
}

std::optional<CustodyReceipt> decode_custody_receipt(std::string_view bytes, uint32_t envelope_id) {
  if (bytes.size() < kCustodyReceiptBytes || !starts_custody_receipt(bytes, envelope_id)) return std::nullopt;
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  CustodyReceipt receipt;
  receipt.verdict = static_cast<CustodyVerdict>(b[2]);
  receipt.about.origin = static_cast<uint16_t>(util::load_le(b + 3, 2));
  receipt.about.seq = static_cast<uint16_t>(util::load_le(b + 5, 2));
  return receipt;
}

const char* to_string(CustodyVerdict verdict) {
  switch (verdict) {
    case CustodyVerdict::kTaken: return "taken";
    case CustodyVerdict::kRefused: return "refused";
  }
  return "?";
}

}  // namespace acomms::route
