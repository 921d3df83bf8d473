#include "delta/delta_codec.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "dccl/numeric.h"

namespace acomms::codecs {
namespace {

namespace pb = google::protobuf;
using dccl::BitReader;
using dccl::BitWriter;
using dccl::ceil_log2;

template <typename T>
T get(const pb::Message& m, const pb::FieldDescriptor* f, int i) {
  if constexpr (std::is_same_v<T, float>) {
    return m.GetReflection()->GetRepeatedFloat(m, f, i);
  } else {
    return m.GetReflection()->GetRepeatedDouble(m, f, i);
  }
}

template <typename T>
void add(pb::Message* m, const pb::FieldDescriptor* f, T v) {
  if constexpr (std::is_same_v<T, float>) {
    m->GetReflection()->AddFloat(m, f, v);
  } else {
    m->GetReflection()->AddDouble(m, f, v);
  }
}

double max_delta_option(const dccl::FieldContext& ctx) {
  const pb::Message* options = ctx.extension_message(kDeltaOptionsExtension);
  if (options == nullptr) {
    ctx.fail("codec acomms.delta needs import \"acomms/codecs/delta.proto\"");
  }
  const pb::FieldDescriptor* max_delta = options->GetDescriptor()->FindFieldByName("max_delta");
  if (max_delta == nullptr || !options->GetReflection()->HasField(*options, max_delta)) {
    ctx.fail("codec acomms.delta needs (acomms.codecs.delta).max_delta");
  }
  double value = options->GetReflection()->GetDouble(*options, max_delta);
  if (!(value > 0) || !std::isfinite(value)) ctx.fail("max_delta must be a positive number");
  return value;
}

template <typename T>
class DeltaCodec final : public dccl::FieldCodec {
 public:
  explicit DeltaCodec(const dccl::FieldContext& ctx)
      : field_(ctx.field), path_(ctx.path), max_delta_(max_delta_option(ctx)) {
    const dccl::FieldOptions& o = ctx.options;
    if (!o.has_min || !o.has_max) ctx.fail("codec acomms.delta needs (dccl.field).min and max");
    if (!o.has_max_repeat) ctx.fail("codec acomms.delta needs (dccl.field).max_repeat");
    if (o.max_repeat < o.min_repeat) ctx.fail("max_repeat is less than min_repeat");
    if (o.has_precision && o.has_resolution) ctx.fail("precision and resolution are both set");
    dccl::NumericBounds bounds{o.min, o.max, o.has_precision ? std::pow(10.0, -o.precision) : o.resolution,
                               o.has_precision, o.precision};
    key_ = dccl::NumericCore<T>(bounds, /*optional=*/false, path_);
    res_ = key_.resolution();
    scale_ = 1.0 / res_;
    // Wire values 1..span+1 are differences -max_delta..+max_delta; 0 is
    // "out of range".
    span_ = static_cast<uint64_t>(std::llround(2 * max_delta_ * scale_));
    delta_bits_ = ceil_log2(span_ + 2);
    min_repeat_ = o.min_repeat;
    max_repeat_ = o.max_repeat;
    count_bits_ = ceil_log2(uint64_t{max_repeat_} - min_repeat_ + 1);
  }

  dccl::SizeBits size() const override {
    auto elements = [this](uint64_t n) {
      return n == 0 ? 0 : key_.bits() + (n - 1) * uint64_t{delta_bits_};
    };
    return {count_bits_ + elements(min_repeat_), count_bits_ + elements(max_repeat_)};
  }

  double resolution() const override { return res_; }

  void encode(const pb::Message& msg, BitWriter& out, const dccl::EncodeContext& ctx) const override {
    const int present = msg.GetReflection()->FieldSize(msg, field_);
    if (present > static_cast<int>(max_repeat_) && ctx.strict) {
      throw dccl::encode_error(path_ + ": " + std::to_string(present) +
                               " elements exceed max_repeat " + std::to_string(max_repeat_));
    }
    const uint32_t count =
        std::max<uint32_t>(min_repeat_, std::min<uint32_t>(present, max_repeat_));
    out.write(count - min_repeat_, count_bits_);
    if (count == 0) return;
    // Missing elements up to min_repeat are sent as zeros, as the default
    // repeated codec does.
    auto value = [&](uint32_t i) { return i < static_cast<uint32_t>(present) ? get<T>(msg, field_, i) : T{}; };
    uint64_t key_wire = key_.to_wire(value(0), ctx, path_);
    out.write(key_wire, key_.bits());
    const double key = static_cast<double>(*key_.from_wire(key_wire));
    for (uint32_t i = 1; i < count; ++i) out.write(delta_to_wire(value(i), key, ctx), delta_bits_);
  }

  void decode(BitReader& in, pb::Message* msg, const dccl::DecodeContext&) const override {
    const uint32_t count = static_cast<uint32_t>(in.read(count_bits_)) + min_repeat_;
    if (count > max_repeat_) {
      throw dccl::decode_error(path_ + ": count " + std::to_string(count) + " exceeds max_repeat " +
                               std::to_string(max_repeat_));
    }
    if (count == 0) return;
    std::optional<T> key = key_.from_wire(in.read(key_.bits()));
    const double k = key ? static_cast<double>(*key) : 0.0;
    add<T>(msg, field_, key.value_or(T{}));
    for (uint32_t i = 1; i < count; ++i) {
      uint64_t u = in.read(delta_bits_);
      if (u == 0 || u > span_ + 1) {
        add<T>(msg, field_, std::numeric_limits<T>::quiet_NaN());
        continue;
      }
      double x = k + (static_cast<double>(u - 1) - max_delta_ * scale_) * res_;
      // Snap to the field's quantum so 0.1 steps decode as 12.3, not 12.2999.
      add<T>(msg, field_, static_cast<T>(std::round(x * scale_) / scale_));
    }
  }

 private:
  uint64_t delta_to_wire(T x, double key, const dccl::EncodeContext& ctx) const {
    double scaled = std::floor((static_cast<double>(x) + max_delta_ - key) * scale_ + 0.5);
    if (!std::isfinite(scaled) || scaled < 0 || scaled > static_cast<double>(span_)) {
      if (ctx.strict) {
        throw dccl::encode_error(path_ + ": " + dccl::format_number(static_cast<double>(x)) +
                                 " is more than max_delta " + dccl::format_number(max_delta_) +
                                 " from the key " + dccl::format_number(key));
      }
      return 0;
    }
    return static_cast<uint64_t>(scaled) + 1;
  }

  const pb::FieldDescriptor* field_;
  std::string path_;
  double max_delta_;
  dccl::NumericCore<T> key_;
  double res_ = 1, scale_ = 1;
  uint64_t span_ = 0;
  unsigned delta_bits_ = 0;
  uint32_t min_repeat_ = 0, max_repeat_ = 0;
  unsigned count_bits_ = 0;
};

std::unique_ptr<dccl::FieldCodec> make_delta_codec(const dccl::FieldContext& ctx) {
  if (!ctx.field->is_repeated()) ctx.fail("codec acomms.delta is for repeated fields");
  switch (ctx.field->cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_DOUBLE: return std::make_unique<DeltaCodec<double>>(ctx);
    case pb::FieldDescriptor::CPPTYPE_FLOAT: return std::make_unique<DeltaCodec<float>>(ctx);
    default: ctx.fail("codec acomms.delta is for float and double fields");
  }
}

}  // namespace

void register_delta_codec(dccl::CodecRegistry& registry) {
  registry.add(kDeltaCodecName, make_delta_codec);
}

}  // namespace acomms::codecs
