// The DCCL wire: how one message of a loaded type becomes bytes and back.
//
// Problem: the bytes must equal the reference DCCL 4 library's, bit for bit,
// or a vehicle running it cannot read us (and we cannot read it). Decision:
// everything that shapes a whole message on the wire lives here, in one
// place, apart from schema loading: the id prefix, the head (in_head fields)
// and body each padded to a byte, and body encryption. The bits of one field
// are its FieldCodec's (default_codecs.cpp, numeric.cpp, special_codecs.cpp);
// the order of fields is the plan's MessageBody (message_codec.cpp).
//
//   id:   one byte `id << 1` for ids below 128, else two bytes little-endian
//         of `(id << 1) | 1`; none for omit_id types
//   head: the in_head fields, then zero bits up to a byte boundary
//   body: the other fields, then zero bits up to a byte boundary;
//         AES-CTR encrypted (crypto.h) unless crypto is off or the id exempt
//   auth: for authenticated types only, a fixed-length trailer (key id,
//         send time, counter, tag: message_auth.h) sealed after encryption;
//         decode consumes it but does not check it (the receive side does,
//         with MessageAuthenticator::verify), so that stored messages
//         still decode after their key retired
//
// Thread safety: encode/decode may run concurrently once the settings are
// made; the set_*() calls must not run concurrently with anything.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "dccl/crypto.h"
#include "dccl/message_auth.h"
#include "dccl/type_plan.h"

namespace google::protobuf {
class Message;
}  // namespace google::protobuf

namespace acomms::dccl {

class WireFormat {
 public:
  WireFormat();

  // `msg` must be of plan's type, from the loader's pool.
  std::string encode(const TypePlan& plan, const google::protobuf::Message& msg) const;
  // One message of plan's type from the start of bytes (whose id, if any,
  // the caller has checked); *consumed gets the bytes used.
  std::unique_ptr<google::protobuf::Message> decode(const TypePlan& plan, std::string_view bytes,
                                                    size_t* consumed) const;

  // The DCCL id that starts bytes. Throws Error if bytes are too short.
  static int id_of(std::string_view bytes);

  void set_crypto(std::string_view passphrase, std::set<int> exempt_ids);
  void clear_crypto();
  // Types (full names) whose messages carry the trailer; null turns it off.
  void set_authentication(std::shared_ptr<const MessageAuthenticator> authenticator, std::set<std::string> types);
  const MessageAuthenticator* authenticator() const { return authenticator_.get(); }
  bool authenticates(const TypeInfo& info) const;
  void set_strict(bool strict) { strict_ = strict; }
  bool strict() const { return strict_; }
  // Null restores the system clock.
  void set_clock(std::function<double()> clock);

 private:
  bool encrypts(const TypeInfo& info) const;
  // `used` bytes of DCCL, plus the trailer when info is authenticated.
  // Throws Error when bytes end inside the trailer.
  size_t with_trailer(const TypeInfo& info, std::string_view bytes, size_t used) const;

  bool strict_ = false;
  std::function<double()> clock_;
  std::optional<BodyCipher> cipher_;
  std::set<int> exempt_ids_;
  std::shared_ptr<const MessageAuthenticator> authenticator_;
  std::set<std::string> authenticated_types_;
};

}  // namespace acomms::dccl
