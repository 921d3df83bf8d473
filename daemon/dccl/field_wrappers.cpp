// The wrappers that turn an element codec into a field codec: singular,
// repeated (v2: always max_repeat optional elements; v3+: count prefix,
// required elements) and presence-bit fields.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <algorithm>
#include <limits>
#include <string>

#include "dccl/element_codec.h"
#include "dccl/numeric.h"
#include "util/saturating.h"

namespace acomms::dccl {
namespace gp = google::protobuf;

namespace {

using util::saturating_add;
using util::saturating_mul;

class SingularField final : public FieldCodec {
 public:
  SingularField(const FieldContext& ctx, std::unique_ptr<ElementCodec> element, bool required)
      : field_(ctx.field), path_(ctx.path), element_(std::move(element)), required_(required) {}

  SizeBits size() const override { return element_->size(); }
  double resolution() const override { return element_->resolution(); }
  void encode(const gp::Message& msg, BitWriter& out, const EncodeContext& ctx) const override {
    if (required_) {
      if (ctx.strict && field_->is_required() && !msg.GetReflection()->HasField(msg, field_)) {
        throw encode_error(path_ + ": required field is not set");
      }
      element_->encode(msg, -1, out, ctx);
    } else if (msg.GetReflection()->HasField(msg, field_)) {
      element_->encode(msg, -1, out, ctx);
    } else {
      element_->encode_unset(msg, out);
    }
  }
  void decode(BitReader& in, gp::Message* msg, const DecodeContext& ctx) const override {
    element_->decode(in, msg, ctx);
  }

 private:
  const gp::FieldDescriptor* field_;
  std::string path_;
  std::unique_ptr<ElementCodec> element_;
  bool required_;
};

std::string too_many(const std::string& path, int n, uint32_t max) {
  return path + ": " + std::to_string(n) + " elements exceed max_repeat " + std::to_string(max);
}

// v3/v4: ceil_log2(max_repeat - min_repeat + 1) bits of count - min_repeat,
// then the elements; missing elements up to min_repeat are zeros.
class RepeatedField final : public FieldCodec {
 public:
  RepeatedField(const FieldContext& ctx, std::unique_ptr<ElementCodec> element)
      : field_(ctx.field),
        path_(ctx.path),
        element_(std::move(element)),
        min_(ctx.options.min_repeat),
        max_(ctx.options.max_repeat),
        prefix_bits_(ceil_log2(uint64_t{max_} - min_ + 1)),
        elem_(element_->size()) {
    if (elem_.max == 0) ctx.fail("repeated field of zero-size elements is not supported");
  }

  SizeBits size() const override {
    return {saturating_add(prefix_bits_, saturating_mul(min_, elem_.min)), saturating_add(prefix_bits_, saturating_mul(max_, elem_.max))};
  }
  double resolution() const override { return element_->resolution(); }

  void encode(const gp::Message& msg, BitWriter& out, const EncodeContext& ctx) const override {
    int n = msg.GetReflection()->FieldSize(msg, field_);
    if (static_cast<uint32_t>(n) > max_) {
      if (ctx.strict) throw encode_error(too_many(path_, n, max_));
      n = static_cast<int>(max_);
    }
    uint32_t count = std::max(static_cast<uint32_t>(n), min_);
    out.write(count - min_, prefix_bits_);
    for (int i = 0; i < n; ++i) element_->encode(msg, i, out, ctx);
    for (uint32_t i = static_cast<uint32_t>(n); i < count; ++i) out.write_zeros(elem_.min);
  }

  void decode(BitReader& in, gp::Message* msg, const DecodeContext& ctx) const override {
    uint64_t count = in.read(prefix_bits_) + min_;
    in.require(saturating_mul(count, elem_.min));  // never loop over more elements than bytes
    for (uint64_t i = 0; i < count; ++i) element_->decode(in, msg, ctx);
  }

 private:
  const gp::FieldDescriptor* field_;
  std::string path_;
  std::unique_ptr<ElementCodec> element_;
  uint32_t min_, max_;
  unsigned prefix_bits_;
  SizeBits elem_;
};

// v2: always max_repeat elements in optional encoding.
class FixedRepeatedField final : public FieldCodec {
 public:
  FixedRepeatedField(const FieldContext& ctx, std::unique_ptr<ElementCodec> element)
      : field_(ctx.field),
        path_(ctx.path),
        element_(std::move(element)),
        max_(ctx.options.max_repeat),
        elem_(element_->size()),
        messages_(ctx.field->cpp_type() == gp::FieldDescriptor::CPPTYPE_MESSAGE) {
    if (elem_.max == 0) ctx.fail("repeated field of zero-size elements is not supported");
  }

  SizeBits size() const override { return {saturating_mul(max_, elem_.min), saturating_mul(max_, elem_.max)}; }
  double resolution() const override { return element_->resolution(); }

  void encode(const gp::Message& msg, BitWriter& out, const EncodeContext& ctx) const override {
    int n = msg.GetReflection()->FieldSize(msg, field_);
    if (static_cast<uint32_t>(n) > max_ && ctx.strict) throw encode_error(too_many(path_, n, max_));
    for (uint32_t i = 0; i < max_; ++i) {
      if (i < static_cast<uint32_t>(n)) {
        element_->encode(msg, static_cast<int>(i), out, ctx);
      } else {
        element_->encode_unset(msg, out);
      }
    }
  }
  void decode(BitReader& in, gp::Message* msg, const DecodeContext& ctx) const override {
    in.require(saturating_mul(max_, elem_.min));
    if (!messages_) {
      for (uint32_t i = 0; i < max_; ++i) element_->decode(in, msg, ctx);
      return;
    }
    const gp::Reflection* r = msg->GetReflection();
    const int before = r->FieldSize(*msg, field_);
    for (uint32_t i = 0; i < max_; ++i) element_->decode(in, msg, ctx);
    // Sub-messages: the reference keeps every element decoded and then
    // drops one from the END for each that came out empty, so an empty
    // element before a non-empty one survives and the non-empty one goes
    // ([{}, {a: 6}] decodes as [{}]). A fielded vehicle decodes this way.
    int empty = 0;
    for (int i = before; i < r->FieldSize(*msg, field_); ++i) {
      if (r->GetRepeatedMessage(*msg, field_, i).ByteSizeLong() == 0) ++empty;
    }
    for (; empty > 0; --empty) r->RemoveLast(msg, field_);
  }

 private:
  const gp::FieldDescriptor* field_;
  std::string path_;
  std::unique_ptr<ElementCodec> element_;
  uint32_t max_;
  SizeBits elem_;
  bool messages_;  // elements are sub-messages
};

// dccl.presence on an optional field: 1 presence bit, then required encoding.
class PresenceField final : public FieldCodec {
 public:
  PresenceField(const FieldContext& ctx, std::unique_ptr<ElementCodec> element)
      : field_(ctx.field), element_(std::move(element)) {}

  SizeBits size() const override { return {1, saturating_add(element_->size().max, 1)}; }
  double resolution() const override { return element_->resolution(); }
  void encode(const gp::Message& msg, BitWriter& out, const EncodeContext& ctx) const override {
    if (msg.GetReflection()->HasField(msg, field_)) {
      out.write(1, 1);
      element_->encode(msg, -1, out, ctx);
    } else {
      out.write(0, 1);
    }
  }
  void decode(BitReader& in, gp::Message* msg, const DecodeContext& ctx) const override {
    if (in.read(1) != 0) element_->decode(in, msg, ctx);
  }

 private:
  const gp::FieldDescriptor* field_;
  std::unique_ptr<ElementCodec> element_;
};

}  // namespace

std::unique_ptr<FieldCodec> make_field(const FieldContext& ctx, const ElementBuilder& build) {
  return make_field(ctx, build, ctx.codec_version);
}

std::unique_ptr<FieldCodec> make_field(const FieldContext& ctx, const ElementBuilder& build, int layout_version) {
  if (ctx.field->is_repeated()) {
    if (layout_version >= 3) return std::make_unique<RepeatedField>(ctx, build(ctx, true));
    return std::make_unique<FixedRepeatedField>(ctx, build(ctx, false));
  }
  return std::make_unique<SingularField>(ctx, build(ctx, ctx.required), ctx.required);
}

std::unique_ptr<FieldCodec> make_presence_field(const FieldContext& ctx, const ElementBuilder& build) {
  if (!ctx.field->is_repeated() && !ctx.required) {
    return std::make_unique<PresenceField>(ctx, build(ctx, true));
  }
  return make_field(ctx, build);
}

}  // namespace acomms::dccl
