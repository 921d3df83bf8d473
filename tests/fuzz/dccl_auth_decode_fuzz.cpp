// libFuzzer target: the authenticated decode (dccl/message_auth.h) of
// untrusted bytes. Every type with an id in the conformance schema is made
// authenticated, bodies encrypted, so that each input goes through the
// trailer (decode consumes it, verify checks it) the way a rogue's frame
// would. Decoding must return messages or throw dccl::Error, and verify
// must return a verdict: any other exception, crash or sanitizer report is
// a bug.
//
// Oracle: whatever decodes re-encodes, and that fresh encoding (sealed now
// with the fleet key) verifies and decodes using exactly its own bytes.

#include <google/protobuf/message.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <set>
#include <string>
#include <string_view>

#include "dccl/codec.h"
#include "dccl/message_auth.h"

namespace {

using acomms::dccl::AuthVerdict;
using acomms::dccl::Codec;
using acomms::dccl::MessageAuthenticator;

constexpr double kNow = 1'700'000'000.0;
constexpr int32_t kSender = 7;  // the transmission's source the tags are made for

struct Fleet {
  Codec codec;
  std::shared_ptr<MessageAuthenticator> auth;
};

std::unique_ptr<Fleet> make_fleet() {
  auto fleet = std::make_unique<Fleet>();
  fleet->codec.load(ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto", {ACOMMS_PROTO_DIR});
  fleet->codec.set_clock([] { return kNow; });
  fleet->codec.set_crypto("fuzz passphrase");
  acomms::dccl::Keyring ring;
  ring.keys[1].key = std::string(16, 'k');
  ring.keys[2].key = std::string(32, 'K');
  ring.keys[2].accept_until = kNow - 1;  // retired
  ring.sign_id = 1;
  fleet->auth = std::make_shared<MessageAuthenticator>(40, ring, kSender);
  std::set<std::string> types;
  for (const auto* type : fleet->codec.types()) {
    // Only types whose largest message still fits max_bytes sealed (the
    // codec refuses the rest).
    if (!type->omit_id && type->max_size_bytes() + fleet->auth->trailer_bytes() <= type->max_bytes) {
      types.insert(type->name);
    }
  }
  fleet->codec.set_authentication(fleet->auth, types);
  return fleet;
}

void check_round_trip(const Fleet& fleet, const google::protobuf::Message& message) {
  std::string sealed = fleet.codec.encode(message);
  // Types too large to seal within their max_bytes are left plain.
  const bool authenticated = fleet.codec.authenticated(message.GetDescriptor()->full_name());
  if (authenticated && fleet.auth->verify(sealed, kNow, kSender, nullptr) != AuthVerdict::kOk) std::abort();
  size_t used = 0;
  auto again = fleet.codec.decode_as(message.GetDescriptor()->full_name(), sealed, &used);
  if (used != sealed.size()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::unique_ptr<Fleet> fleet = make_fleet();
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  size_t offset = 0;
  // As the receive side unstitches a frame: decode, check the trailer, go on.
  while (offset < bytes.size()) {
    std::string_view rest = bytes.substr(offset);
    try {
      const auto* type = fleet->codec.find_id(fleet->codec.id_of(rest));
      if (type == nullptr) break;
      size_t used = 0;
      auto message = fleet->codec.decode_as(type->name, rest, &used);
      if (used == 0 || used > rest.size()) std::abort();
      acomms::dccl::AuthStamp stamp;
      (void)fleet->auth->verify(rest.substr(0, used), kNow, kSender, &stamp);
      check_round_trip(*fleet, *message);
      offset += used;
    } catch (const acomms::dccl::Error&) {
      break;
    }
  }
  // The trailer check alone, on any length.
  (void)fleet->auth->verify(bytes, kNow, kSender, nullptr);
  return 0;
}
