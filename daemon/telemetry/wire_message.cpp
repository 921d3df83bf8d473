#include "telemetry/wire_message.h"

#include <stdexcept>

#include "dccl/codec.h"

namespace acomms::telemetry {
namespace gp = google::protobuf;

bool is_telemetry_type(std::string_view type) {
  return type == kFullType || type == kDeltaType || type == kFeedbackType;
}

std::vector<bool> body_of(const EncodedMessage& message) {
  std::vector<bool> body;
  body.reserve(message.body_bits);
  dccl::BitReader in(message.bytes, kHeaderBits);
  for (uint64_t i = 0; i < message.body_bits; ++i) body.push_back(in.read(1) != 0);
  return body;
}

std::string library_bytes(const WireMessage& message) {
  std::string bytes;
  dccl::BitWriter out(&bytes);
  write_header(out, Header{message.kind, message.sequence % kSequenceModulus});
  for (bool bit : message.body) out.write(bit ? 1 : 0, 1);
  return bytes;
}

std::unique_ptr<gp::Message> to_dccl(const dccl::Codec& codec, const WireMessage& message) {
  const bool full = message.kind == MessageKind::kFull;
  const size_t max_bits = full ? kMaxFullBodyBits : kMaxDeltaBodyBits;
  if (message.body.size() > max_bits) {
    throw std::invalid_argument("telemetry " + std::string(full ? "full" : "delta") + " body of " +
                                std::to_string(message.body.size()) + " bits exceeds " + std::to_string(max_bits));
  }
  if (message.sequence >= kWireSequenceModulus) throw std::invalid_argument("telemetry sequence out of range");
  std::unique_ptr<gp::Message> out = codec.new_message(full ? kFullType : kDeltaType);
  const gp::Descriptor* d = out->GetDescriptor();
  const gp::Reflection* r = out->GetReflection();
  r->SetInt32(out.get(), d->FindFieldByName("src"), message.src);
  r->SetInt32(out.get(), d->FindFieldByName("dest"), message.dest);
  r->SetUInt32(out.get(), d->FindFieldByName("sequence"), message.sequence);
  const gp::FieldDescriptor* body = d->FindFieldByName("body");
  for (bool bit : message.body) r->AddBool(out.get(), body, bit);
  return out;
}

WireMessage from_dccl(const gp::Message& message) {
  const gp::Descriptor* d = message.GetDescriptor();
  WireMessage out;
  if (d->full_name() == kFullType) {
    out.kind = MessageKind::kFull;
  } else if (d->full_name() == kDeltaType) {
    out.kind = MessageKind::kDelta;
  } else {
    throw std::invalid_argument(d->full_name() + " is not a telemetry type");
  }
  const gp::Reflection* r = message.GetReflection();
  auto field = [&](const char* name) {
    const gp::FieldDescriptor* f = d->FindFieldByName(name);
    if (f == nullptr) throw std::invalid_argument(d->full_name() + " has no field " + name);
    return f;
  };
  out.src = r->GetInt32(message, field("src"));
  out.dest = r->GetInt32(message, field("dest"));
  out.sequence = r->GetUInt32(message, field("sequence"));
  if (out.sequence >= kWireSequenceModulus) {
    throw std::invalid_argument(d->full_name() + ".sequence " + std::to_string(out.sequence) + " is not below " +
                                std::to_string(kWireSequenceModulus));
  }
  const gp::FieldDescriptor* body = field("body");
  const int n = r->FieldSize(message, body);
  const size_t max_bits = out.kind == MessageKind::kFull ? kMaxFullBodyBits : kMaxDeltaBodyBits;
  if (static_cast<size_t>(n) > max_bits) {
    throw std::invalid_argument(d->full_name() + ".body has " + std::to_string(n) + " bits, more than " +
                                std::to_string(max_bits));
  }
  out.body.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) out.body.push_back(r->GetRepeatedBool(message, body, i));
  return out;
}

std::unique_ptr<gp::Message> to_dccl(const dccl::Codec& codec, const WireFeedback& feedback) {
  if (feedback.heard && *feedback.heard >= kWireSequenceModulus)
    throw std::invalid_argument("telemetry feedback: heard out of range");
  std::unique_ptr<gp::Message> out = codec.new_message(kFeedbackType);
  const gp::Descriptor* d = out->GetDescriptor();
  const gp::Reflection* r = out->GetReflection();
  r->SetInt32(out.get(), d->FindFieldByName("src"), feedback.src);
  r->SetInt32(out.get(), d->FindFieldByName("dest"), feedback.dest);
  r->SetUInt32(out.get(), d->FindFieldByName("heard"), feedback.heard.value_or(kWireSequenceModulus));
  return out;
}

WireFeedback feedback_from_dccl(const gp::Message& message) {
  const gp::Descriptor* d = message.GetDescriptor();
  if (d->full_name() != kFeedbackType) throw std::invalid_argument(d->full_name() + " is not telemetry feedback");
  const gp::Reflection* r = message.GetReflection();
  const gp::FieldDescriptor* src = d->FindFieldByName("src");
  const gp::FieldDescriptor* dest = d->FindFieldByName("dest");
  const gp::FieldDescriptor* heard = d->FindFieldByName("heard");
  if (src == nullptr || dest == nullptr || heard == nullptr)
    throw std::invalid_argument(d->full_name() + " lacks src, dest or heard");
  WireFeedback out;
  out.src = r->GetInt32(message, src);
  out.dest = r->GetInt32(message, dest);
  const uint32_t value = r->GetUInt32(message, heard);
  if (value > kWireSequenceModulus)
    throw std::invalid_argument(d->full_name() + ".heard " + std::to_string(value) + " is above 4096");
  if (value < kWireSequenceModulus) out.heard = value;
  return out;
}

int32_t sequence_distance(uint32_t a, uint32_t b) {
  const uint32_t m = kWireSequenceModulus;
  const uint32_t diff = (a + m - (b % m)) % m;
  return diff >= m / 2 ? static_cast<int32_t>(diff) - static_cast<int32_t>(m) : static_cast<int32_t>(diff);
}

}  // namespace acomms::telemetry
