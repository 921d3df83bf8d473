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

// dccl.time: the time of day within a num_days window, on a double field
// (seconds since the epoch) or an (u)int64 one (microseconds). As in the
// reference, which a fielded vehicle runs:
//  - a microsecond value is converted to double seconds first (so values
//    above 2^53 us lose precision, and half a step rounds as the double
//    does), and then coded exactly like a double time;
//  - the time of day is fmod(seconds, window): a negative time gives a
//    negative time of day, out of range (all zeros; strict mode refuses it);
//  - precision on a microsecond field counts in microseconds (precision -3:
//    steps of 1 ms) but resolution counts in seconds (resolution 0.001:
//    steps of 1 ms), default 1 s;
//  - the decoder puts the time of day in the window within half a window of
//    its clock, then rounds the result to the precision (whole seconds when
//    only a resolution is given: 1.5 s at resolution 0.5 decodes as 2 s).
template <typename T>
class TimeElement final : public ElementCodec {
 public:
  TimeElement(const FieldContext& ctx, bool required) : field_(ctx.field), path_(ctx.path) {
    const FieldOptions& o = ctx.options;
    if (o.num_days == 0) ctx.fail("dccl.time needs num_days >= 1");
    window_s_ = o.num_days * kSecondsPerDay;
    // Precision as a power of ten of seconds.
    const int64_t p64 = std::is_floating_point_v<T> ? int64_t{o.precision} : int64_t{o.precision} + 6;
    if (o.has_precision && (p64 < -300 || p64 > 300)) {
      ctx.fail("precision " + std::to_string(o.precision) + " is out of range");
    }
    const int32_t precision = static_cast<int32_t>(p64);
    NumericBounds b;
    b.max = window_s_;
    b.has_precision = o.has_precision;
    b.precision = precision;
    b.resolution = o.has_precision ? std::pow(10.0, -precision) : o.resolution;
    core_ = NumericCore<double>(b, !required, path_);
    decode_scale_ = std::pow(10.0, o.has_precision ? precision : 0);
  }

  SizeBits size() const override { return {core_.bits(), core_.bits()}; }
  double resolution() const override {
    return std::is_floating_point_v<T> ? core_.resolution() : core_.resolution() * 1e6;
  }

  void encode(const gp::Message& msg, int index, BitWriter& out, const EncodeContext& ctx) const override {
    const T x = Access<T>::get(msg, field_, index);
    const double seconds = std::is_floating_point_v<T> ? static_cast<double>(x) : static_cast<double>(x) / 1e6;
    out.write(core_.to_wire(std::fmod(seconds, window_s_), ctx, path_), core_.bits());
  }
  void encode_unset(const gp::Message&, BitWriter& out) const override { out.write(0, core_.bits()); }

  void decode(BitReader& in, gp::Message* msg, const DecodeContext& ctx) const override {
    std::optional<double> v = core_.from_wire(in.read(core_.bits()));
    if (!v) return;
    double now = ctx.now();
    if (!std::isfinite(now)) now = 0;
    const double k = std::floor((now - *v) / window_s_ + 0.5);
    const double t = *v + k * window_s_;
    const double seconds =
        decode_scale_ == 1 ? std::floor(t + 0.5) : std::floor(t * decode_scale_ + 0.5) / decode_scale_;
    if constexpr (std::is_floating_point_v<T>) {
      Access<T>::put(msg, field_, seconds);
    } else {
      // Defined for every clock: a far-off clock saturates.
      double us = std::floor(seconds * 1e6 + 0.5);
      if (std::is_unsigned_v<T> && !(us >= 0)) us = 0;
      Access<T>::put(msg, field_, static_cast<T>(x86_double_to_u64(us)));
    }
  }

 private:
  const gp::FieldDescriptor* field_;
  std::string path_;
  double window_s_ = kSecondsPerDay;
  double decode_scale_ = 1;  // 10^precision: the decoder rounds to it
  NumericCore<double> core_;
};

// The reference reads static_value with `istream >> value`: only the first
// whitespace-separated word counts, for strings too ("hello world" decodes
// as "hello").
std::string first_word(const std::string& text) {
  size_t b = text.find_first_not_of(" \t\n\v\f\r");
  if (b == std::string::npos) return "";
  size_t e = text.find_first_of(" \t\n\v\f\r", b);
  return text.substr(b, e == std::string::npos ? std::string::npos : e - b);
}

// dccl.static: no bits; every decoded message gets the first word of
// static_value.
class StaticElement final : public ElementCodec {
 public:
  StaticElement(const FieldContext& ctx) : field_(ctx.field), text_(first_word(ctx.options.static_value)) {
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
        // The reference has no dccl.static for enums: it refuses the type,
        // so no fielded vehicle sends it.
        throw TypeRefused(ctx.path + ": dccl.static does not support enum fields (the reference DCCL refuses this type)");
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
      case gp::FieldDescriptor::CPPTYPE_ENUM:  // refused at load
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
