// libFuzzer target: DCCL encoding of what a client submits. Submit takes a
// message as protobuf bytes (or JSON, parsed into the same message), so any
// protobuf a client can build reaches the encoder. For every type in the
// conformance schema (gv.proto), bytes that parse as that type must either
// encode or be refused with dccl::Error; and what encodes must decode back
// as that type and encode again to the same bytes (strict mode, as acommsd
// runs, and the reference library's lenient mode). Anything else is a bug.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include <google/protobuf/message.h>
#include <google/protobuf/stubs/logging.h>

#include "dccl/codec.h"

namespace {

using acomms::dccl::Codec;

std::unique_ptr<Codec> make_codec(bool strict) {
  auto codec = std::make_unique<Codec>();
  codec->load(ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto", {ACOMMS_PROTO_DIR});
  codec->set_clock([] { return 1'700'000'000.0; });
  codec->set_strict(strict);
  return codec;
}

void check(const Codec& codec, const std::string& type, std::string_view bytes) {
  std::unique_ptr<google::protobuf::Message> message = codec.new_message(type);
  if (!message->ParsePartialFromArray(bytes.data(), static_cast<int>(bytes.size()))) return;
  std::string encoded;
  try {
    encoded = codec.encode(*message);
  } catch (const acomms::dccl::Error&) {
    return;
  }
  // Encoded by us, so it must decode, whatever the input was.
  size_t consumed = 0;
  std::unique_ptr<google::protobuf::Message> decoded = codec.decode_as(type, encoded, &consumed);
  if (consumed != encoded.size()) __builtin_trap();
  // Decoding may round a value (precision, time of day), so only the second
  // round trip must be exact.
  std::string again;
  try {
    again = codec.encode(*decoded);
  } catch (const acomms::dccl::Error&) {
    // A decoded message is always within bounds. But, as the reference
    // does, an empty v2/v3 string or sub-message decodes as not set (README,
    // "Matching the reference"): a required one is then missing, which only
    // strict mode refuses. Anything else is a bug.
    if (codec.strict() && !decoded->IsInitialized()) return;
    __builtin_trap();
  }
  if (codec.encode(*codec.decode_as(type, again)) != again) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Parsing logs every string field that is not UTF-8: noise here, and slow.
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::unique_ptr<Codec> strict = make_codec(true);
  static const std::unique_ptr<Codec> lenient = make_codec(false);
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (const auto* type : strict->types()) {
    check(*strict, type->name, bytes);
    check(*lenient, type->name, bytes);
  }
  return 0;
}
