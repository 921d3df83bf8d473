// Built-in codecs are written per value ("element"); small wrappers turn an
// element codec into a FieldCodec for a singular, repeated (v2: always
// max_repeat optional elements; v3+: count prefix) or presence-bit field.
// Internal to the library.
#pragma once

#include <functional>
#include <memory>

#include "dccl/field_codec.h"

namespace acomms::dccl {

class ElementCodec {
 public:
  virtual ~ElementCodec() = default;
  virtual SizeBits size() const = 0;
  // Writes the value at `index` (-1: the singular field), which is set.
  virtual void encode(const google::protobuf::Message& msg, int index, BitWriter& out,
                      const EncodeContext& ctx) const = 0;
  // Writes the "not set" form (optional encoding only).
  virtual void encode_unset(const google::protobuf::Message& msg, BitWriter& out) const = 0;
  // Reads one value; sets it (singular) or appends it (repeated) unless the
  // wire says "not set".
  virtual void decode(BitReader& in, google::protobuf::Message* msg, const DecodeContext& ctx) const = 0;
  virtual double resolution() const { return 0; }
};

// Builds the element codec for ctx.field in required or optional encoding.
using ElementBuilder =
    std::function<std::unique_ptr<ElementCodec>(const FieldContext& ctx, bool required)>;

// The _default codec's element for any field type.
std::unique_ptr<ElementCodec> make_default_element(const FieldContext& ctx, bool required);
// dccl.time, dccl.static and dccl.var_bytes elements.
std::unique_ptr<ElementCodec> make_time_element(const FieldContext& ctx, bool required);
std::unique_ptr<ElementCodec> make_static_element(const FieldContext& ctx, bool required);
std::unique_ptr<ElementCodec> make_var_bytes_element(const FieldContext& ctx, bool required);

// Wraps elements into a field codec following the version's rules for
// singular and repeated fields.
std::unique_ptr<FieldCodec> make_field(const FieldContext& ctx, const ElementBuilder& build);
// The same with the repeated layout of codec version `layout_version`: an
// explicit older codec (dccl.default2) in a newer message builds its
// elements by its own version's rules but keeps the message's repeated
// layout, as the reference does.
std::unique_ptr<FieldCodec> make_field(const FieldContext& ctx, const ElementBuilder& build, int layout_version);
// dccl.presence: optional singular fields get one presence bit and then the
// required encoding; everything else as make_field.
std::unique_ptr<FieldCodec> make_presence_field(const FieldContext& ctx, const ElementBuilder& build);

}  // namespace acomms::dccl
