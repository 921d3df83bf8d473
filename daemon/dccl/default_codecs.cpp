// The _default codec's element codecs: numbers, bool, enum, string/bytes,
// embedded messages (field_wrappers.cpp turns them into field codecs).
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "dccl/element_codec.h"
#include "dccl/message_codec.h"
#include "dccl/numeric.h"
#include "dccl/reflection_access.h"
#include "util/saturating.h"

namespace acomms::dccl {
namespace gp = google::protobuf;

namespace {

using util::saturating_add;

NumericBounds numeric_bounds(const FieldContext& ctx) {
  const FieldOptions& o = ctx.options;
  if (!o.has_min || !o.has_max) ctx.fail("numeric field needs (dccl.field).min and max");
  NumericBounds b;
  b.min = o.min;
  b.max = o.max;
  b.has_precision = o.has_precision;
  b.precision = o.precision;
  b.resolution = o.has_precision ? std::pow(10.0, -o.precision) : o.resolution;
  return b;
}

// ---------------------------------------------------------------- numbers

template <typename T>
class NumericElement final : public ElementCodec {
 public:
  NumericElement(const FieldContext& ctx, bool required)
      : field_(ctx.field), path_(ctx.path), core_(numeric_bounds(ctx), !required, ctx.path) {}

  SizeBits size() const override { return {core_.bits(), core_.bits()}; }
  void encode(const gp::Message& msg, int index, BitWriter& out, const EncodeContext& ctx) const override {
    out.write(core_.to_wire(Access<T>::get(msg, field_, index), ctx, path_), core_.bits());
  }
  void encode_unset(const gp::Message&, BitWriter& out) const override { out.write(0, core_.bits()); }
  void decode(BitReader& in, gp::Message* msg, const DecodeContext&) const override {
    if (std::optional<T> v = core_.from_wire(in.read(core_.bits()))) Access<T>::put(msg, field_, *v);
  }
  double resolution() const override { return core_.resolution(); }

 private:
  const gp::FieldDescriptor* field_;
  std::string path_;
  NumericCore<T> core_;
};

// ---------------------------------------------------------------- bool

// Required: 1 bit. Optional: 2 bits, 0 = not set, 1 = false, 2 = true.
class BoolElement final : public ElementCodec {
 public:
  BoolElement(const FieldContext& ctx, bool required) : field_(ctx.field), required_(required) {}

  SizeBits size() const override { return required_ ? SizeBits{1, 1} : SizeBits{2, 2}; }
  void encode(const gp::Message& msg, int index, BitWriter& out, const EncodeContext&) const override {
    bool v = Access<bool>::get(msg, field_, index);
    if (required_) {
      out.write(v ? 1 : 0, 1);
    } else {
      out.write(v ? 2 : 1, 2);
    }
  }
  void encode_unset(const gp::Message&, BitWriter& out) const override { out.write(0, 2); }
  void decode(BitReader& in, gp::Message* msg, const DecodeContext&) const override {
    if (required_) {
      Access<bool>::put(msg, field_, in.read(1) != 0);
      return;
    }
    uint64_t v = in.read(2);
    if (v == 1 || v == 2) Access<bool>::put(msg, field_, v == 2);
  }

 private:
  const gp::FieldDescriptor* field_;
  bool required_;
};

// ---------------------------------------------------------------- enum

// The declaration index 0..n-1 (packed, and always in v2) or the enum
// number over [lowest number, highest number], by the numeric rule.
class EnumElement final : public ElementCodec {
 public:
  EnumElement(const FieldContext& ctx, bool required)
      : field_(ctx.field),
        enum_(ctx.field->enum_type()),
        path_(ctx.path),
        packed_(ctx.options.packed_enum || ctx.codec_version == 2) {
    NumericBounds b;
    if (packed_) {
      b.min = 0;
      b.max = enum_->value_count() - 1;
    } else {
      int lo = enum_->value(0)->number(), hi = lo;
      for (int i = 1; i < enum_->value_count(); ++i) {
        lo = std::min(lo, enum_->value(i)->number());
        hi = std::max(hi, enum_->value(i)->number());
      }
      b.min = lo;
      b.max = hi;
    }
    core_ = NumericCore<int32_t>(b, !required, path_);
  }

  SizeBits size() const override { return {core_.bits(), core_.bits()}; }
  void encode(const gp::Message& msg, int index, BitWriter& out, const EncodeContext& ctx) const override {
    const gp::Reflection* r = msg.GetReflection();
    const gp::EnumValueDescriptor* v =
        index < 0 ? r->GetEnum(msg, field_) : r->GetRepeatedEnum(msg, field_, index);
    out.write(core_.to_wire(packed_ ? v->index() : v->number(), ctx, path_), core_.bits());
  }
  void encode_unset(const gp::Message&, BitWriter& out) const override { out.write(0, core_.bits()); }
  void decode(BitReader& in, gp::Message* msg, const DecodeContext&) const override {
    std::optional<int32_t> n = core_.from_wire(in.read(core_.bits()));
    if (!n) return;
    const gp::EnumValueDescriptor* v = nullptr;
    if (packed_) {
      if (*n >= 0 && *n < enum_->value_count()) v = enum_->value(*n);
    } else {
      v = enum_->FindValueByNumber(*n);
    }
    if (v == nullptr) return;  // no such value: decodes as not set
    const gp::Reflection* r = msg->GetReflection();
    if (field_->is_repeated()) {
      r->AddEnum(msg, field_, v);
    } else {
      r->SetEnum(msg, field_, v);
    }
  }

 private:
  const gp::FieldDescriptor* field_;
  const gp::EnumDescriptor* enum_;
  std::string path_;
  bool packed_;
  NumericCore<int32_t> core_;
};

// ---------------------------------------------------------------- string / bytes

enum class StringRule {
  kV2,     // 8-bit length + bytes; length 0 = not set
  kV3,     // ceil_log2(max_length+1)-bit length + bytes; "" = not set
  kV4,     // optional: presence bit, then length + bytes (also dccl.var_bytes)
  kFixed,  // v2/v3 bytes: max_length bytes zero padded; optional: presence bit first
};

class StringElement final : public ElementCodec {
 public:
  StringElement(const FieldContext& ctx, bool required, StringRule rule)
      : field_(ctx.field), path_(ctx.path), rule_(rule), required_(required) {
    if (!ctx.options.has_max_length) ctx.fail("string/bytes field needs (dccl.field).max_length");
    max_len_ = ctx.options.max_length;
    if (rule == StringRule::kV2 && max_len_ > 255) {
      ctx.fail("max_length " + std::to_string(max_len_) + " does not fit the 8-bit length of codec_version 2");
    }
    len_bits_ = rule == StringRule::kV2 ? 8 : ceil_log2(uint64_t{max_len_} + 1);
    presence_ = !required && (rule == StringRule::kV4 || rule == StringRule::kFixed);
  }

  SizeBits size() const override {
    uint64_t bytes = uint64_t{max_len_} * 8;
    uint64_t p = presence_ ? 1 : 0;
    if (rule_ == StringRule::kFixed) return presence_ ? SizeBits{1, 1 + bytes} : SizeBits{bytes, bytes};
    return {presence_ ? 1 : len_bits_, p + len_bits_ + bytes};
  }

  void encode(const gp::Message& msg, int index, BitWriter& out, const EncodeContext& ctx) const override {
    const gp::Reflection* r = msg.GetReflection();
    std::string scratch;
    const std::string& s = index < 0 ? r->GetStringReference(msg, field_, &scratch)
                                     : r->GetRepeatedStringReference(msg, field_, index, &scratch);
    size_t n = s.size();
    if (n > max_len_) {
      if (ctx.strict) {
        throw encode_error(path_ + ": length " + std::to_string(n) + " exceeds max_length " +
                           std::to_string(max_len_));
      }
      n = max_len_;
    }
    if (presence_) out.write(1, 1);
    std::string_view bytes(s.data(), n);
    if (rule_ == StringRule::kFixed) {
      out.write_bytes(bytes);
      out.write_zeros((uint64_t{max_len_} - n) * 8);
      return;
    }
    out.write(n, len_bits_);
    out.write_bytes(bytes);
  }

  void encode_unset(const gp::Message&, BitWriter& out) const override {
    if (presence_) {
      out.write(0, 1);
    } else {
      out.write(0, len_bits_);
    }
  }

  void decode(BitReader& in, gp::Message* msg, const DecodeContext&) const override {
    if (presence_ && in.read(1) == 0) return;
    std::string value;
    if (rule_ == StringRule::kFixed) {
      in.read_bytes(max_len_, &value);
    } else {
      uint64_t n = in.read(len_bits_);
      // v2/v3: length 0 is "not set", required fields (and presence-coded
      // ones) included: the reference decodes them so.
      bool empty_is_unset = rule_ == StringRule::kV2 || rule_ == StringRule::kV3;
      if (n == 0 && empty_is_unset) return;
      in.read_bytes(n, &value);
    }
    const gp::Reflection* r = msg->GetReflection();
    if (field_->is_repeated()) {
      r->AddString(msg, field_, std::move(value));
    } else {
      r->SetString(msg, field_, std::move(value));
    }
  }

 private:
  const gp::FieldDescriptor* field_;
  std::string path_;
  StringRule rule_;
  bool required_;
  uint32_t max_len_ = 0;
  unsigned len_bits_ = 0;
  bool presence_ = false;
};

// ---------------------------------------------------------------- embedded message

// v3/v4 optional: a presence bit, then the body. v2 always writes the body
// (an unset message as its default instance); a decoded v2 message with
// nothing set is dropped again.
class MessageElement final : public ElementCodec {
 public:
  MessageElement(const FieldContext& ctx, bool required)
      : field_(ctx.field),
        v2_(ctx.codec_version == 2),
        presence_(!required && ctx.codec_version >= 3),
        body_(ctx.compiler->compile_embedded(ctx.field->message_type(), ctx.path)) {}

  SizeBits size() const override {
    SizeBits b = body_->size();
    return presence_ ? SizeBits{1, saturating_add(b.max, 1)} : b;
  }
  void encode(const gp::Message& msg, int index, BitWriter& out, const EncodeContext& ctx) const override {
    const gp::Reflection* r = msg.GetReflection();
    const gp::Message& sub = index < 0 ? r->GetMessage(msg, field_) : r->GetRepeatedMessage(msg, field_, index);
    if (presence_) out.write(1, 1);
    body_->encode(sub, out, ctx);
  }
  void encode_unset(const gp::Message& msg, BitWriter& out) const override {
    if (presence_) {
      out.write(0, 1);
      return;
    }
    const gp::Message* prototype =
        msg.GetReflection()->GetMessageFactory()->GetPrototype(field_->message_type());
    body_->encode(*prototype, out, EncodeContext{});
  }
  void decode(BitReader& in, gp::Message* msg, const DecodeContext& ctx) const override {
    if (presence_ && in.read(1) == 0) return;
    const gp::Reflection* r = msg->GetReflection();
    gp::Message* sub = field_->is_repeated() ? r->AddMessage(msg, field_) : r->MutableMessage(msg, field_);
    body_->decode(in, sub, ctx);
    // v2: a sub-message with nothing set decodes as absent, required ones
    // included (as the reference does); the repeated wrapper drops empty
    // elements its own way.
    if (v2_ && !field_->is_repeated() && sub->ByteSizeLong() == 0) r->ClearField(msg, field_);
  }

 private:
  const gp::FieldDescriptor* field_;
  bool v2_;
  bool presence_;
  std::shared_ptr<MessageBody> body_;
};

}  // namespace

std::unique_ptr<ElementCodec> make_default_element(const FieldContext& ctx, bool required) {
  const gp::FieldDescriptor* f = ctx.field;
  switch (f->cpp_type()) {
    case gp::FieldDescriptor::CPPTYPE_INT32:
      return std::make_unique<NumericElement<int32_t>>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_INT64:
      return std::make_unique<NumericElement<int64_t>>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_UINT32:
      return std::make_unique<NumericElement<uint32_t>>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_UINT64:
      return std::make_unique<NumericElement<uint64_t>>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_DOUBLE:
      return std::make_unique<NumericElement<double>>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_FLOAT:
      return std::make_unique<NumericElement<float>>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_BOOL:
      return std::make_unique<BoolElement>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_ENUM:
      return std::make_unique<EnumElement>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_STRING: {
      StringRule rule = StringRule::kV4;
      if (f->type() == gp::FieldDescriptor::TYPE_BYTES) {
        if (ctx.codec_version < 4) rule = StringRule::kFixed;
      } else if (ctx.codec_version == 2) {
        rule = StringRule::kV2;
      } else if (ctx.codec_version == 3) {
        rule = StringRule::kV3;
      }
      return std::make_unique<StringElement>(ctx, required, rule);
    }
    case gp::FieldDescriptor::CPPTYPE_MESSAGE:
      return std::make_unique<MessageElement>(ctx, required);
  }
  ctx.fail("field type not supported");
}

std::unique_ptr<ElementCodec> make_var_bytes_element(const FieldContext& ctx, bool required) {
  if (ctx.field->cpp_type() != gp::FieldDescriptor::CPPTYPE_STRING) {
    ctx.fail("dccl.var_bytes needs a string or bytes field");
  }
  return std::make_unique<StringElement>(ctx, required, StringRule::kV4);
}

}  // namespace acomms::dccl
