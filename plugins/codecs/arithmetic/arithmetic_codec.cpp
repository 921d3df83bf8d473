#include "arithmetic/arithmetic_codec.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "dccl/arithmetic_coder.h"
#include "dccl/numeric.h"

namespace acomms::codecs {
namespace {

namespace pb = google::protobuf;
using dccl::BitReader;
using dccl::BitWriter;

// The coding alphabet: these two, then value symbol i at kFirstValue + i.
// This order (and EOF before the values) is what the reference vector needs.
constexpr size_t kOutOfRange = 0;
constexpr size_t kEof = 1;
constexpr size_t kFirstValue = 2;

struct Options {
  std::string model;
  bool debug_assert = false;
};

Options read_options(const dccl::FieldContext& ctx) {
  const pb::Message* ext = ctx.extension_message(kArithmeticOptionsExtension);
  if (ext == nullptr) {
    ctx.fail("codec dccl.arithmetic needs import \"dccl/arithmetic/protobuf/arithmetic_extensions.proto\"");
  }
  const pb::Descriptor* d = ext->GetDescriptor();
  const pb::Reflection* r = ext->GetReflection();
  Options o;
  const pb::FieldDescriptor* model = d->FindFieldByName("model");
  if (model != nullptr && model->cpp_type() == pb::FieldDescriptor::CPPTYPE_STRING && !model->is_repeated()) {
    o.model = r->GetString(*ext, model);
  }
  const pb::FieldDescriptor* debug = d->FindFieldByName("debug_assert");
  if (debug != nullptr && debug->cpp_type() == pb::FieldDescriptor::CPPTYPE_BOOL && !debug->is_repeated()) {
    o.debug_assert = r->GetBool(*ext, debug);
  }
  if (o.model.empty()) ctx.fail("codec dccl.arithmetic needs (dccl.field).(arithmetic).model");
  return o;
}

// ceil(x) as an integer of [lo, hi], saturating (bounds of integer fields
// need not be integers or within the type).
template <typename I>
I ceil_clamped(double x) {
  const double c = std::ceil(x);
  if (c <= static_cast<double>(std::numeric_limits<I>::min())) return std::numeric_limits<I>::min();
  // max() of 64-bit types rounds up to 2^63 / 2^64 as a double.
  if (c >= static_cast<double>(std::numeric_limits<I>::max())) return std::numeric_limits<I>::max();
  return static_cast<I>(c);
}

// Information content, in bits, of a symbol of probability p after the
// coder's integer rounding (which can take 2^-30 off a probability).
double cost_bits(double p) { return -std::log2(p - std::ldexp(1.0, -30)); }

class ArithmeticCodec final : public dccl::FieldCodec {
 public:
  ArithmeticCodec(const dccl::FieldContext& ctx, const Options& options, const ArithmeticModel& model)
      : field_(ctx.field),
        path_(ctx.path),
        model_(model),
        debug_assert_(options.debug_assert),
        present_if_unset_(ctx.required),
        max_(ctx.field->is_repeated() ? ctx.options.max_repeat : 1) {
    frequencies_ = {model.out_of_range_frequency, model.eof_frequency};
    frequencies_.insert(frequencies_.end(), model.frequency.begin(), model.frequency.end());
    uint64_t total = 0;
    for (uint32_t f : frequencies_) total += f;
    if (model.is_adaptive && total + max_ > dccl::arith::kMaxTotalFrequency) {
      ctx.fail("adaptive arithmetic model \"" + model.name + "\" could exceed total frequency " +
               std::to_string(dccl::arith::kMaxTotalFrequency) + " over max_repeat " + std::to_string(max_) +
               " symbols");
    }
    // Values are compared in the field's own type, so a float field holding
    // 100.1f falls in the symbol that starts at 100.1.
    bounds_ = model.value_bound;
    if (field_->cpp_type() == pb::FieldDescriptor::CPPTYPE_FLOAT) {
      for (double& b : bounds_) b = static_cast<double>(static_cast<float>(b));
      for (size_t i = 1; i < bounds_.size(); ++i) {
        if (!(bounds_[i] > bounds_[i - 1])) {
          ctx.fail("arithmetic model \"" + model.name + "\" has value_bound " +
                   dccl::format_number(model.value_bound[i - 1]) + " and " +
                   dccl::format_number(model.value_bound[i]) + " that are equal as float");
        }
      }
    }
    size_ = compute_size(total);
  }

  dccl::SizeBits size() const override { return size_; }

  void encode(const pb::Message& msg, BitWriter& out, const dccl::EncodeContext& ctx) const override {
    const std::vector<size_t> symbols = symbols_of(msg, ctx);
    // Coded into a buffer of our own so debug_assert can read it back.
    std::string buffer;
    BitWriter bits(&buffer);
    dccl::arith::FrequencyTable table(frequencies_);
    dccl::arith::Encoder encoder(bits);
    for (size_t s : symbols) {
      encoder.encode(table, s);
      if (model_.is_adaptive) table.increment(s);
    }
    encoder.finish();
    const uint64_t length = bits.position();
    if (debug_assert_) check_decodes(buffer, length, symbols);
    BitReader copy(buffer);
    for (uint64_t left = length; left > 0;) {
      const unsigned n = static_cast<unsigned>(std::min<uint64_t>(left, 64));
      out.write(copy.read(n), n);
      left -= n;
    }
  }

  void decode(BitReader& in, pb::Message* msg, const dccl::DecodeContext&) const override {
    dccl::arith::FrequencyTable table(frequencies_);
    dccl::arith::Decoder decoder(in);
    for (uint32_t n = 0; n < max_; ++n) {
      const size_t s = decoder.decode(table);
      if (s == kEof) break;
      if (model_.is_adaptive) table.increment(s);
      store(msg, s);
    }
  }

 private:
  dccl::SizeBits compute_size(uint64_t total) const {
    // Probabilities can only fall to frequency / (largest total reached).
    const double t = static_cast<double>(total + (model_.is_adaptive ? max_ : 0));
    uint32_t rarest = model_.frequency.front();
    for (uint32_t f : model_.frequency) rarest = std::min(rarest, f);
    if (model_.out_of_range_frequency > 0) rarest = std::min(rarest, model_.out_of_range_frequency);
    const double element = cost_bits(rarest / t);
    double worst = max_ * element;
    if (model_.eof_frequency > 0) {
      const double ended = (max_ > 0 ? (max_ - 1) * element : 0.0) + cost_bits(model_.eof_frequency / t);
      worst = std::max(worst, ended);
    }
    // + 2: the final flush needs at most 2 bits more than the information
    // content; + 1: margin for the floating point above.
    return {0, static_cast<uint64_t>(std::ceil(worst)) + 3};
  }

  // The element (index, or -1 for a singular field) as a number to compare
  // with the bounds.
  double value_at(const pb::Message& msg, int index) const {
    const pb::Reflection* r = msg.GetReflection();
    const bool rep = index >= 0;
    switch (field_->cpp_type()) {
      case pb::FieldDescriptor::CPPTYPE_DOUBLE:
        return rep ? r->GetRepeatedDouble(msg, field_, index) : r->GetDouble(msg, field_);
      case pb::FieldDescriptor::CPPTYPE_FLOAT:
        return rep ? r->GetRepeatedFloat(msg, field_, index) : r->GetFloat(msg, field_);
      case pb::FieldDescriptor::CPPTYPE_INT32:
        return rep ? r->GetRepeatedInt32(msg, field_, index) : r->GetInt32(msg, field_);
      case pb::FieldDescriptor::CPPTYPE_INT64:
        return static_cast<double>(rep ? r->GetRepeatedInt64(msg, field_, index) : r->GetInt64(msg, field_));
      case pb::FieldDescriptor::CPPTYPE_UINT32:
        return rep ? r->GetRepeatedUInt32(msg, field_, index) : r->GetUInt32(msg, field_);
      case pb::FieldDescriptor::CPPTYPE_UINT64:
        return static_cast<double>(rep ? r->GetRepeatedUInt64(msg, field_, index) : r->GetUInt64(msg, field_));
      case pb::FieldDescriptor::CPPTYPE_ENUM:
        return rep ? r->GetRepeatedEnumValue(msg, field_, index) : r->GetEnumValue(msg, field_);
      case pb::FieldDescriptor::CPPTYPE_BOOL:
        return (rep ? r->GetRepeatedBool(msg, field_, index) : r->GetBool(msg, field_)) ? 1.0 : 0.0;
      default:
        return std::numeric_limits<double>::quiet_NaN();  // rejected at load
    }
  }

  size_t symbol_of(double v) const {
    if (!(v >= bounds_.front() && v < bounds_.back())) return kOutOfRange;
    auto it = std::upper_bound(bounds_.begin(), bounds_.end(), v);
    return kFirstValue + static_cast<size_t>(it - bounds_.begin()) - 1;
  }

  std::vector<size_t> symbols_of(const pb::Message& msg, const dccl::EncodeContext& ctx) const {
    const pb::Reflection* r = msg.GetReflection();
    const bool repeated = field_->is_repeated();
    uint64_t present = repeated ? static_cast<uint64_t>(r->FieldSize(msg, field_))
                                : (r->HasField(msg, field_) || present_if_unset_ ? 1 : 0);
    if (present > max_) {
      if (ctx.strict) {
        throw dccl::encode_error(path_ + ": " + std::to_string(present) + " elements exceed max_repeat " +
                                 std::to_string(max_));
      }
      present = max_;
    }
    std::vector<size_t> symbols;
    for (uint64_t i = 0; i < present; ++i) {
      const double v = value_at(msg, repeated ? static_cast<int>(i) : -1);
      const size_t s = symbol_of(v);
      if (s == kOutOfRange && model_.out_of_range_frequency == 0) {
        if (ctx.strict) {
          throw dccl::encode_error(path_ + ": " + dccl::format_number(v) + " is outside arithmetic model \"" +
                                   model_.name + "\" [" + dccl::format_number(bounds_.front()) + ", " +
                                   dccl::format_number(bounds_.back()) + ")");
        }
        break;  // the list ends at the first value that cannot be sent
      }
      symbols.push_back(s);
    }
    if (symbols.size() < max_) {
      if (model_.eof_frequency == 0) {
        throw dccl::encode_error(path_ + ": arithmetic model \"" + model_.name +
                                 "\" has eof_frequency 0, so exactly " + std::to_string(max_) +
                                 " values are needed (can send " + std::to_string(symbols.size()) + ")");
      }
      symbols.push_back(kEof);
    }
    return symbols;
  }

  // Adds (repeated) or sets (singular) the decoded value of symbol.
  void store(pb::Message* msg, size_t symbol) const {
    const pb::Reflection* r = msg->GetReflection();
    auto put = [&](auto add, auto set, auto value) {
      if (field_->is_repeated()) {
        (r->*add)(msg, field_, value);
      } else {
        (r->*set)(msg, field_, value);
      }
    };
    using R = pb::Reflection;
    const pb::FieldDescriptor::CppType type = field_->cpp_type();
    if (symbol == kOutOfRange) {
      // Floating point fields say "not a value"; others have no way to.
      if (type == pb::FieldDescriptor::CPPTYPE_DOUBLE) {
        put(&R::AddDouble, &R::SetDouble, std::numeric_limits<double>::quiet_NaN());
      } else if (type == pb::FieldDescriptor::CPPTYPE_FLOAT) {
        put(&R::AddFloat, &R::SetFloat, std::numeric_limits<float>::quiet_NaN());
      }
      return;
    }
    const double b = model_.value_bound[symbol - kFirstValue];
    switch (type) {
      case pb::FieldDescriptor::CPPTYPE_DOUBLE: put(&R::AddDouble, &R::SetDouble, b); break;
      case pb::FieldDescriptor::CPPTYPE_FLOAT: put(&R::AddFloat, &R::SetFloat, static_cast<float>(b)); break;
      case pb::FieldDescriptor::CPPTYPE_INT32: put(&R::AddInt32, &R::SetInt32, ceil_clamped<int32_t>(b)); break;
      case pb::FieldDescriptor::CPPTYPE_INT64: put(&R::AddInt64, &R::SetInt64, ceil_clamped<int64_t>(b)); break;
      case pb::FieldDescriptor::CPPTYPE_UINT32: put(&R::AddUInt32, &R::SetUInt32, ceil_clamped<uint32_t>(b)); break;
      case pb::FieldDescriptor::CPPTYPE_UINT64: put(&R::AddUInt64, &R::SetUInt64, ceil_clamped<uint64_t>(b)); break;
      case pb::FieldDescriptor::CPPTYPE_BOOL: put(&R::AddBool, &R::SetBool, std::ceil(b) != 0); break;
      case pb::FieldDescriptor::CPPTYPE_ENUM: {
        const int number = ceil_clamped<int32_t>(b);
        // A bound that is no value of the enum decodes as no value.
        if (field_->enum_type()->FindValueByNumber(number) != nullptr) {
          put(&R::AddEnumValue, &R::SetEnumValue, number);
        }
        break;
      }
      default: break;
    }
  }

  // debug_assert: what was written must decode to the same symbols and end
  // on the last bit written.
  void check_decodes(const std::string& buffer, uint64_t length, const std::vector<size_t>& symbols) const {
    BitReader in(buffer);
    dccl::arith::FrequencyTable table(frequencies_);
    dccl::arith::Decoder decoder(in);
    for (size_t expected : symbols) {
      size_t got;
      try {
        got = decoder.decode(table);
      } catch (const dccl::TruncatedRead&) {
        got = symbols.size() + kFirstValue + model_.frequency.size();  // no such symbol
      }
      if (got != expected || in.position() > length) {
        throw dccl::encode_error(path_ + ": arithmetic debug_assert: encoding does not decode back");
      }
      if (model_.is_adaptive) table.increment(got);
    }
    if (in.position() != length) {
      throw dccl::encode_error(path_ + ": arithmetic debug_assert: decoder would read " +
                               std::to_string(in.position()) + " of " + std::to_string(length) + " bits");
    }
  }

  const pb::FieldDescriptor* field_;
  std::string path_;
  ArithmeticModel model_;
  bool debug_assert_;
  bool present_if_unset_;  // required encoding: an unset singular field sends its default
  uint32_t max_;           // most elements: max_repeat, or 1 for a singular field
  std::vector<uint32_t> frequencies_;  // in coding order (kOutOfRange, kEof, values)
  std::vector<double> bounds_;         // value_bound in the field's type
  dccl::SizeBits size_;
};

std::unique_ptr<dccl::FieldCodec> make_arithmetic_codec(const dccl::FieldContext& ctx,
                                                       const ArithmeticModels& models) {
  switch (ctx.field->cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_STRING:
    case pb::FieldDescriptor::CPPTYPE_MESSAGE:
      ctx.fail("codec dccl.arithmetic is for numeric, enum and bool fields");
    default:
      break;
  }
  const Options options = read_options(ctx);
  std::optional<ArithmeticModel> model = models.find(options.model);
  if (!model) ctx.fail("arithmetic model \"" + options.model + "\" is not registered");
  return std::make_unique<ArithmeticCodec>(ctx, options, *model);
}

}  // namespace

void register_arithmetic_codec(dccl::CodecRegistry& registry, std::shared_ptr<const ArithmeticModels> models) {
  registry.add(kArithmeticCodecName, [models = std::move(models)](const dccl::FieldContext& ctx) {
    return make_arithmetic_codec(ctx, *models);
  });
}

}  // namespace acomms::codecs
