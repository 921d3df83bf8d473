// dccl.time and dccl.static element codecs.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "dccl/element_codec.h"
#include "dccl/numeric.h"
#include "dccl/reflection_access.h"

namespace acomms::dccl {
namespace gp = google::protobuf;

namespace {

constexpr double kSecondsPerDay = 86400;

// dccl.time: the time of day (within a num_days window), double seconds or
// (u)int64 microseconds since the epoch. Resolution defaults to 1 s; for
// microsecond fields precision/resolution are in microseconds. The decoder
// puts the value in the window that is within half a window of its clock.
template <typename T>
class TimeElement final : public ElementCodec {
 public:
  TimeElement(const FieldContext& ctx, bool required) : field_(ctx.field), path_(ctx.path) {
    const FieldOptions& o = ctx.options;
    if (o.num_days == 0) ctx.fail("dccl.time needs num_days >= 1");
    window_s_ = o.num_days * kSecondsPerDay;
    NumericBounds b;
    b.has_precision = o.has_precision;
    b.precision = o.precision;
    if constexpr (std::is_floating_point_v<T>) {
      b.max = window_s_;
      b.resolution = o.has_precision ? std::pow(10.0, -o.precision) : o.resolution;
    } else {
      if (o.num_days > 100000) ctx.fail("dccl.time num_days is too large for a microsecond field");
      window_us_ = static_cast<__int128>(o.num_days) * 86400 * 1000000;
      b.max = static_cast<double>(window_us_);
      b.resolution = o.has_precision    ? std::pow(10.0, -o.precision)
                     : o.has_resolution ? o.resolution
                                        : 1e6;
    }
    core_ = NumericCore<T>(b, !required, path_);
  }

  SizeBits size() const override { return {core_.bits(), core_.bits()}; }
  double resolution() const override { return core_.resolution(); }

  void encode(const gp::Message& msg, int index, BitWriter& out, const EncodeContext& ctx) const override {
    T x = Access<T>::get(msg, field_, index);
    T wrapped;
    if constexpr (std::is_floating_point_v<T>) {
      wrapped = x - std::floor(x / window_s_) * window_s_;
    } else {
      __int128 v = x;
      wrapped = static_cast<T>(((v % window_us_) + window_us_) % window_us_);
    }
    out.write(core_.to_wire(wrapped, ctx, path_), core_.bits());
  }
  void encode_unset(const gp::Message&, BitWriter& out) const override { out.write(0, core_.bits()); }

  void decode(BitReader& in, gp::Message* msg, const DecodeContext& ctx) const override {
    std::optional<T> v = core_.from_wire(in.read(core_.bits()));
    if (!v) return;
    double now = ctx.now();
    if (!std::isfinite(now)) now = 0;
    if constexpr (std::is_floating_point_v<T>) {
      double k = std::floor((now - *v) / window_s_ + 0.5);
      Access<T>::put(msg, field_, static_cast<T>(*v + k * window_s_));
    } else {
      double now_us = now * 1e6;
      if (now_us > 9e18) now_us = 9e18;
      if (now_us < -9e18) now_us = -9e18;
      __int128 diff = static_cast<__int128>(now_us) - static_cast<__int128>(*v);
      __int128 shifted = diff + window_us_ / 2;
      __int128 k = shifted / window_us_;
      if (shifted % window_us_ < 0) --k;  // floor division
      __int128 result = static_cast<__int128>(*v) + k * window_us_;
      if (result < 0 && std::is_unsigned_v<T>) result = *v;
      Access<T>::put(msg, field_, static_cast<T>(result));
    }
  }

 private:
  const gp::FieldDescriptor* field_;
  std::string path_;
  double window_s_ = kSecondsPerDay;
  __int128 window_us_ = 1;
  NumericCore<T> core_;
};

// dccl.static: no bits; every decoded message gets static_value.
class StaticElement final : public ElementCodec {
 public:
  StaticElement(const FieldContext& ctx) : field_(ctx.field), text_(ctx.options.static_value) {
    auto bad = [&]() {
      ctx.fail("static_value \"" + text_ + "\" is not a valid " + field_->type_name());
    };
    const char* s = text_.c_str();
    char* end = nullptr;
    errno = 0;
    switch (field_->cpp_type()) {
      case gp::FieldDescriptor::CPPTYPE_STRING:
        break;
      case gp::FieldDescriptor::CPPTYPE_INT32:
      case gp::FieldDescriptor::CPPTYPE_INT64:
        i_ = std::strtoll(s, &end, 10);
        break;
      case gp::FieldDescriptor::CPPTYPE_UINT32:
      case gp::FieldDescriptor::CPPTYPE_UINT64:
        u_ = std::strtoull(s, &end, 10);
        break;
      case gp::FieldDescriptor::CPPTYPE_DOUBLE:
      case gp::FieldDescriptor::CPPTYPE_FLOAT:
        d_ = std::strtod(s, &end);
        break;
      case gp::FieldDescriptor::CPPTYPE_BOOL:
        if (text_ != "true" && text_ != "false" && text_ != "1" && text_ != "0") bad();
        b_ = text_ == "true" || text_ == "1";
        break;
      case gp::FieldDescriptor::CPPTYPE_ENUM:
        e_ = field_->enum_type()->FindValueByName(text_);
        if (e_ == nullptr) bad();
        break;
      case gp::FieldDescriptor::CPPTYPE_MESSAGE:
        ctx.fail("dccl.static does not support message fields");
    }
    if (end != nullptr && (end == s || *end != '\0' || errno == ERANGE)) bad();
    if (field_->cpp_type() == gp::FieldDescriptor::CPPTYPE_FLOAT && std::fabs(d_) > 3.4e38) bad();
  }

  SizeBits size() const override { return {0, 0}; }
  void encode(const gp::Message&, int, BitWriter&, const EncodeContext&) const override {}
  void encode_unset(const gp::Message&, BitWriter&) const override {}
  void decode(BitReader&, gp::Message* msg, const DecodeContext&) const override {
    const gp::Reflection* r = msg->GetReflection();
    switch (field_->cpp_type()) {
      case gp::FieldDescriptor::CPPTYPE_STRING: r->SetString(msg, field_, text_); break;
      case gp::FieldDescriptor::CPPTYPE_INT32: r->SetInt32(msg, field_, static_cast<int32_t>(i_)); break;
      case gp::FieldDescriptor::CPPTYPE_INT64: r->SetInt64(msg, field_, i_); break;
      case gp::FieldDescriptor::CPPTYPE_UINT32: r->SetUInt32(msg, field_, static_cast<uint32_t>(u_)); break;
      case gp::FieldDescriptor::CPPTYPE_UINT64: r->SetUInt64(msg, field_, u_); break;
      case gp::FieldDescriptor::CPPTYPE_DOUBLE: r->SetDouble(msg, field_, d_); break;
      case gp::FieldDescriptor::CPPTYPE_FLOAT: r->SetFloat(msg, field_, static_cast<float>(d_)); break;
      case gp::FieldDescriptor::CPPTYPE_BOOL: r->SetBool(msg, field_, b_); break;
      case gp::FieldDescriptor::CPPTYPE_ENUM: r->SetEnum(msg, field_, e_); break;
      case gp::FieldDescriptor::CPPTYPE_MESSAGE: break;
    }
  }

 private:
  const gp::FieldDescriptor* field_;
  std::string text_;
  long long i_ = 0;
  unsigned long long u_ = 0;
  double d_ = 0;
  bool b_ = false;
  const gp::EnumValueDescriptor* e_ = nullptr;
};

}  // namespace

std::unique_ptr<ElementCodec> make_time_element(const FieldContext& ctx, bool required) {
  switch (ctx.field->cpp_type()) {
    case gp::FieldDescriptor::CPPTYPE_DOUBLE:
      return std::make_unique<TimeElement<double>>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_INT64:
      return std::make_unique<TimeElement<int64_t>>(ctx, required);
    case gp::FieldDescriptor::CPPTYPE_UINT64:
      return std::make_unique<TimeElement<uint64_t>>(ctx, required);
    default:
      ctx.fail("dccl.time needs a double (seconds) or int64/uint64 (microseconds) field");
  }
}

std::unique_ptr<ElementCodec> make_static_element(const FieldContext& ctx, bool) {
  if (ctx.field->is_repeated()) ctx.fail("dccl.static cannot be used on a repeated field");
  return std::make_unique<StaticElement>(ctx);
}

}  // namespace acomms::dccl
