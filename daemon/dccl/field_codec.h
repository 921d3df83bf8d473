// The field codec interface: how one field of a DCCL message becomes bits.
//
// Every field is encoded by a FieldCodec chosen by name at load time from
// (dccl.field).codec (or the message's codec_group, else "_default"); a name
// without a trailing digit is looked up as name + codec_version first, so
// "dccl.time" in a version 4 message tries "dccl.time4" and then
// "dccl.time". Built-in codecs register through the same CodecRegistry as
// plugins, so a plugin can also replace one.
//
// A FieldCodecFactory runs once per field when a schema loads. It receives a
// FieldContext, checks the options it needs (throwing ctx.fail("...") for a
// broken rule, which becomes "pkg.Msg.field: ..." in the load error), and
// returns a codec with everything precomputed: encode() and decode() run for
// every message and must not look anything up by name.
//
// A codec owns the whole field, repeated elements included, and accesses
// the value through protobuf reflection with ctx.field (messages are
// google::protobuf::DynamicMessage instances of the loaded schema).
//
// Threads: a factory runs while a schema loads (Codec::load, one thread); the
// FieldCodec it returns is then only read, and its encode() and decode() run
// on many threads at once (codec.h), so a codec keeps no mutable state.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "dccl/bitstream.h"
#include "dccl/error.h"
#include "dccl/options.h"

namespace google::protobuf {
class DescriptorPool;
class FieldDescriptor;
class Message;
}  // namespace google::protobuf

namespace acomms::dccl {

class MessageCompiler;

// Bits a field can take on the wire. Load-time validation adds these up to
// check max_bytes and to insist that in_head fields have min == max.
struct SizeBits {
  uint64_t min = 0;
  uint64_t max = 0;
};

struct EncodeContext {
  // Strict mode: out-of-range values, over-long strings and too many repeats
  // throw instead of being zeroed/truncated as the reference encoder does.
  bool strict = false;
};

struct DecodeContext {
  // The receiver's clock, seconds since the Unix epoch (dccl.time picks the
  // day window around it). Never null.
  const std::function<double()>* clock = nullptr;
  double now() const { return (*clock)(); }
};

// What a factory knows about the field it builds a codec for.
struct FieldContext {
  const google::protobuf::FieldDescriptor* field = nullptr;
  // Dotted path from the top-level message, used in every error message:
  // "gv.Embed4.o.v".
  std::string path;
  // Resolved codec name ("_default4", "dccl.time", ...).
  std::string codec_name;
  // The standard options, parsed.
  FieldOptions options;
  // The dccl.DCCLFieldOptions message itself, extensions (1000+) included:
  // plugins read their own options from it with reflection; see extension().
  const google::protobuf::Message* raw_options = nullptr;
  // Pool that holds the schema (to look up extension descriptors).
  const google::protobuf::DescriptorPool* pool = nullptr;
  int codec_version = 4;
  // True when this field's values use DCCL's required encoding (no "unset"
  // value): required fields; repeated elements from v3; oneof members in v4.
  bool required = false;
  // Builds nested message codecs; used by the built-in message codec.
  MessageCompiler* compiler = nullptr;

  // Throws the schema Error "<path>: <rule>".
  [[noreturn]] void fail(const std::string& rule) const { throw schema_error(path + ": " + rule); }
  // The value of extension `full_name` (e.g. "dccl.arithmetic") on this
  // field's DCCLFieldOptions, or nullptr if that extension is not known. For
  // message-typed extensions this is the sub-message (default if unset).
  const google::protobuf::Message* extension_message(std::string_view full_name) const;
  const google::protobuf::FieldDescriptor* extension_field(std::string_view full_name) const;
};

class FieldCodec {
 public:
  virtual ~FieldCodec() = default;

  virtual SizeBits size() const = 0;
  // Writes the field's value(s) taken from msg.
  virtual void encode(const google::protobuf::Message& msg, BitWriter& out,
                      const EncodeContext& ctx) const = 0;
  // Reads the field and stores it in msg (leaving it unset when the wire
  // says so). Reads past the end throw TruncatedRead; other malformed input
  // should throw decode_error("...").
  virtual void decode(BitReader& in, google::protobuf::Message* msg,
                      const DecodeContext& ctx) const = 0;
  // For numeric codecs: the quantum of the value (for tools); 0 otherwise.
  virtual double resolution() const { return 0; }
};

using FieldCodecFactory = std::function<std::unique_ptr<FieldCodec>(const FieldContext&)>;

}  // namespace acomms::dccl
