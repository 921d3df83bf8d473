// libFuzzer target: DCCL decoding of untrusted bytes, for every type in the
// conformance schema (gv.proto). Bytes from a modem are attacker- or
// noise-controlled, so decode must either return messages or throw
// dccl::Error: any other exception, crash or sanitizer report is a bug.
//
// Each input is tried three ways: decode() dispatching on the id, decode_as()
// for every loaded type (which also covers omit_id types), and decode() with
// encryption on. A message that decodes must re-encode without error.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include <google/protobuf/message.h>

#include "dccl/codec.h"

namespace {

using acomms::dccl::Codec;

std::unique_ptr<Codec> make_codec(bool crypto) {
  auto codec = std::make_unique<Codec>();
  codec->load(ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto", {ACOMMS_PROTO_DIR});
  codec->set_clock([] { return 1'700'000'000.0; });
  if (crypto) codec->set_crypto("fuzz passphrase");
  return codec;
}

void reencode(const Codec& codec, const std::vector<std::unique_ptr<google::protobuf::Message>>& messages) {
  for (const auto& message : messages) (void)codec.encode(*message);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::unique_ptr<Codec> plain = make_codec(false);
  static const std::unique_ptr<Codec> encrypted = make_codec(true);
  std::string_view bytes(reinterpret_cast<const char*>(data), size);

  try {
    reencode(*plain, plain->decode(bytes));
  } catch (const acomms::dccl::Error&) {
  }
  for (const auto* type : plain->types()) {
    try {
      size_t consumed = 0;
      auto message = plain->decode_as(type->name, bytes, &consumed);
      if (consumed > size) __builtin_trap();  // claims to have read past the input
      (void)plain->encode(*message);
    } catch (const acomms::dccl::Error&) {
    }
  }
  try {
    reencode(*encrypted, encrypted->decode(bytes));
  } catch (const acomms::dccl::Error&) {
  }
  return 0;
}
