// acomms::dccl::Codec: load DCCL message definitions from .proto files at
// run time, then encode and decode those messages byte-for-byte like the
// reference DCCL 4 library (codec versions 2, 3 and 4).
//
//   acomms::dccl::Codec codec;
//   codec.load("/etc/acommsd/gv.proto", {"/etc/acommsd/proto"});
//   auto msg = codec.new_message("gv.NavigationReport");
//   ... set fields with reflection or TextFormat ...
//   std::string bytes = codec.encode(*msg);
//   for (auto& m : codec.decode(bytes)) ...   // several messages may be concatenated
//
// Loading compiles each type into a plan (every field's codec, bit width and
// bounds resolved), so encode/decode do no option or descriptor look-ups.
// How a file loads: schema_loader.h. How a message becomes bytes (id, head,
// body, padding, encryption): wire_format.h.
// All failures throw acomms::dccl::Error (see error.h).
//
// Messages are google::protobuf::DynamicMessage objects owned by the caller
// but built from this Codec's descriptor pool: they must not outlive it.
// encode() also accepts a message of another class with the same full name
// (e.g. generated C++) at the cost of a copy.
//
// Thread safety: after loading and configuration, encode/decode/new_message
// may be called concurrently; load() and the set_*() calls must not run
// concurrently with anything else.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "dccl/error.h"
#include "dccl/registry.h"
#include "dccl/type_info.h"

namespace google::protobuf {
class Descriptor;
class Message;
}  // namespace google::protobuf

namespace acomms::dccl {

class MessageAuthenticator;
class SchemaLoader;
class WireFormat;

class Codec {
 public:
  // Include directories start with where dccl/option_extensions.proto lives:
  // ../share/acommsd/proto beside the executable when installed there, then
  // ACOMMS_PROTO_DIR when the library was built with it.
  Codec();
  ~Codec();
  Codec(const Codec&) = delete;
  Codec& operator=(const Codec&) = delete;

  // Field codecs available to load(); register plugin codecs here first.
  CodecRegistry& registry();

  // Adds a directory that imports are resolved against.
  void add_include_dir(const std::string& dir);
  // Those directories, in search order.
  const std::vector<std::string>& include_dirs() const;

  // Loads every message with a (dccl.msg) option in proto_file (a disk path,
  // or a path relative to an include directory) and returns their infos.
  // Loading is all or nothing: the Error lists every problem, one per line
  // ("file:line:col: text" for .proto syntax, "pkg.Msg.field: rule" for DCCL
  // rules), and a file that fails leaves no trace, so that its corrected
  // version loads. Loading an unchanged file again is harmless; a file (or
  // an import) that changed since it was loaded is refused, because loaded
  // types cannot be replaced.
  // One exception: a type that the reference DCCL refuses, or that uses a
  // feature acommsd cannot encode like it (TypeRefused), is left out alone,
  // with its reason in refused_types(); the file's other types load.
  std::vector<const TypeInfo*> load(const std::string& proto_file,
                                    const std::vector<std::string>& include_dirs = {});

  // Types left out at load, full name -> reason ("" from refusal() when the
  // type was not refused).
  const std::map<std::string, std::string>& refused_types() const;
  std::string refusal(std::string_view full_name) const;

  // Loaded types; nullptr if unknown.
  const TypeInfo* find_type(std::string_view full_name) const;
  const TypeInfo* find_id(int id) const;
  std::vector<const TypeInfo*> types() const;
  // From now on a type with DCCL id `id` does not load: load() refuses it
  // as a rule error naming `owner` (a gateway's routing.envelope_id marks
  // its envelopes in frames; a type with that id would be read as one).
  // Types already loaded are not checked (the caller does). At start-up,
  // before the codec is shared (as load()).
  void reserve_id(int id, const std::string& owner);

  // An empty message of a loaded type. Throws Error if not loaded.
  std::unique_ptr<google::protobuf::Message> new_message(std::string_view full_name) const;

  // Encodes one message: head (id, in_head fields) and body, each padded to a
  // byte, body encrypted when crypto is on.
  std::string encode(const google::protobuf::Message& msg) const;

  // Decodes every message in bytes (messages concatenated back to back).
  std::vector<std::unique_ptr<google::protobuf::Message>> decode(std::string_view bytes) const;
  // Decodes one message of a known type from the start of bytes (the only
  // way to decode omit_id types); *consumed gets the bytes used.
  std::unique_ptr<google::protobuf::Message> decode_as(std::string_view full_name, std::string_view bytes,
                                                       size_t* consumed = nullptr) const;

  // The DCCL id that starts bytes. Throws Error if bytes are too short.
  int id_of(std::string_view bytes) const;

  // Turns on body encryption (see crypto.h); messages whose id is in
  // exempt_ids stay in clear. An empty passphrase still encrypts.
  void set_crypto(std::string_view passphrase, std::set<int> exempt_ids = {});
  void clear_crypto();

  // Authenticated types (message_auth.h): each message of these loaded
  // types (full names) carries a key id, send time, counter and tag after
  // its DCCL bytes; encode() seals it, decode consumes it without checking
  // it (the receive side calls authenticator()->verify). Throws Error
  // naming a type that is not loaded, has no id, or whose largest message
  // with the trailer is more than its max_bytes (so a sealed message
  // always fits the frame its type was sized for). Null turns it off.
  void set_authentication(std::shared_ptr<const MessageAuthenticator> authenticator, std::set<std::string> types);
  // Null when authentication is off.
  const MessageAuthenticator* authenticator() const;
  bool authenticated(std::string_view full_name) const;

  // Strict mode: encode() throws instead of zeroing out-of-range values,
  // truncating strings/bytes, dropping repeats past max_repeat or encoding a
  // missing required field. Off by default (the reference behaviour).
  void set_strict(bool strict);
  bool strict() const;

  // Clock used by dccl.time when decoding (seconds since the Unix epoch).
  void set_clock(std::function<double()> clock);

 private:
  // Loading (schema_loader.h) and the bytes (wire_format.h) are separate
  // ideas; this class only joins them.
  std::unique_ptr<SchemaLoader> schema_;
  std::unique_ptr<WireFormat> wire_;
};

}  // namespace acomms::dccl
