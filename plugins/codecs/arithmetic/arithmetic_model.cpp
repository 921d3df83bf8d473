#include "arithmetic/arithmetic_model.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <cmath>

#include "dccl/arithmetic_coder.h"
#include "dccl/error.h"
#include "dccl/numeric.h"

namespace acomms::codecs {
namespace {

namespace pb = google::protobuf;

// The descriptor of acomms.codecs.v1.ArithmeticModel, built here rather than
// generated so the codec library does not carry (and clash with) generated
// code that configuration libraries may also compile. Must match
// api/proto/acomms/codecs/arithmetic_model.proto (a test checks that).
const pb::Descriptor* model_descriptor() {
  static const pb::Descriptor* descriptor = [] {
    pb::FileDescriptorProto file;
    file.set_name("acomms/codecs/arithmetic_model.proto");
    file.set_package("acomms.codecs.v1");
    file.set_syntax("proto2");
    pb::DescriptorProto* m = file.add_message_type();
    m->set_name("ArithmeticModel");
    auto add = [&](const char* name, int number, pb::FieldDescriptorProto::Type type,
                   pb::FieldDescriptorProto::Label label, const char* default_value = nullptr) {
      pb::FieldDescriptorProto* f = m->add_field();
      f->set_name(name);
      f->set_number(number);
      f->set_type(type);
      f->set_label(label);
      if (default_value != nullptr) f->set_default_value(default_value);
    };
    using F = pb::FieldDescriptorProto;
    add("name", 1, F::TYPE_STRING, F::LABEL_OPTIONAL);
    add("frequency", 10, F::TYPE_UINT32, F::LABEL_REPEATED);
    add("eof_frequency", 11, F::TYPE_UINT32, F::LABEL_OPTIONAL, "1");
    add("out_of_range_frequency", 12, F::TYPE_UINT32, F::LABEL_OPTIONAL, "0");
    add("value_bound", 20, F::TYPE_DOUBLE, F::LABEL_REPEATED);
    add("is_adaptive", 30, F::TYPE_BOOL, F::LABEL_OPTIONAL, "false");
    static pb::DescriptorPool pool;
    return pool.BuildFile(file)->message_type(0);
  }();
  return descriptor;
}

class TextErrors : public pb::io::ErrorCollector {
 public:
  void AddError(int line, pb::io::ColumnNumber column, const std::string& message) override {
    if (!first.empty()) return;
    first = std::to_string(line + 1) + ":" + std::to_string(column + 1) + ": " + message;
  }
  std::string first;
};

[[noreturn]] void fail(const ArithmeticModel& model, const std::string& rule) {
  throw dccl::schema_error("arithmetic model \"" + model.name + "\": " + rule);
}

}  // namespace

void ArithmeticModel::validate() const {
  if (name.empty()) fail(*this, "needs a name");
  if (frequency.empty()) fail(*this, "needs at least one symbol (frequency)");
  if (value_bound.size() != frequency.size() + 1) {
    fail(*this, "needs one value_bound more than frequency (has " + std::to_string(value_bound.size()) +
                    " and " + std::to_string(frequency.size()) + ")");
  }
  for (size_t i = 0; i < value_bound.size(); ++i) {
    if (!std::isfinite(value_bound[i])) fail(*this, "value_bound must be finite numbers");
    if (i > 0 && !(value_bound[i] > value_bound[i - 1])) {
      fail(*this, "value_bound must be strictly increasing (" + dccl::format_number(value_bound[i - 1]) +
                      " then " + dccl::format_number(value_bound[i]) + ")");
    }
  }
  uint64_t total = uint64_t{eof_frequency} + out_of_range_frequency;
  for (size_t i = 0; i < frequency.size(); ++i) {
    // A symbol of frequency 0 could never be sent, not even adaptively.
    if (frequency[i] == 0) fail(*this, "frequency of symbol " + std::to_string(i) + " is 0");
    total += frequency[i];
  }
  if (total > dccl::arith::kMaxTotalFrequency) {
    fail(*this, "total frequency " + std::to_string(total) + " exceeds " +
                    std::to_string(dccl::arith::kMaxTotalFrequency));
  }
}

ArithmeticModel ArithmeticModel::from_message(const pb::Message& message) {
  const pb::Descriptor* d = message.GetDescriptor();
  const pb::Reflection* r = message.GetReflection();
  ArithmeticModel model;
  auto field = [&](const char* name, pb::FieldDescriptor::CppType type, bool repeated) {
    const pb::FieldDescriptor* f = d->FindFieldByName(name);
    if (f == nullptr) return f;
    if (f->cpp_type() != type || f->is_repeated() != repeated) {
      throw dccl::schema_error("arithmetic model message " + d->full_name() + ": field " + name +
                               " has the wrong type");
    }
    return f;
  };
  if (auto f = field("name", pb::FieldDescriptor::CPPTYPE_STRING, false)) model.name = r->GetString(message, f);
  if (auto f = field("frequency", pb::FieldDescriptor::CPPTYPE_UINT32, true)) {
    for (int i = 0; i < r->FieldSize(message, f); ++i) model.frequency.push_back(r->GetRepeatedUInt32(message, f, i));
  }
  if (auto f = field("value_bound", pb::FieldDescriptor::CPPTYPE_DOUBLE, true)) {
    for (int i = 0; i < r->FieldSize(message, f); ++i) model.value_bound.push_back(r->GetRepeatedDouble(message, f, i));
  }
  // Get* returns the declared default when unset (1 for eof_frequency).
  if (auto f = field("eof_frequency", pb::FieldDescriptor::CPPTYPE_UINT32, false)) {
    model.eof_frequency = r->GetUInt32(message, f);
  }
  if (auto f = field("out_of_range_frequency", pb::FieldDescriptor::CPPTYPE_UINT32, false)) {
    model.out_of_range_frequency = r->GetUInt32(message, f);
  }
  if (auto f = field("is_adaptive", pb::FieldDescriptor::CPPTYPE_BOOL, false)) {
    model.is_adaptive = r->GetBool(message, f);
  }
  return model;
}

ArithmeticModel ArithmeticModel::parse_text(std::string_view text) {
  pb::DynamicMessageFactory factory;
  std::unique_ptr<pb::Message> message(factory.GetPrototype(model_descriptor())->New());
  pb::TextFormat::Parser parser;
  TextErrors errors;
  parser.RecordErrorsTo(&errors);
  if (!parser.ParseFromString(std::string(text), message.get())) {
    throw dccl::schema_error("arithmetic model text: " + errors.first);
  }
  return from_message(*message);
}

void ArithmeticModels::add(const ArithmeticModel& model) {
  model.validate();
  std::lock_guard<std::mutex> lock(mutex_);
  models_[model.name] = model;
}

void ArithmeticModels::remove(const std::string& name) {
  std::lock_guard<std::mutex> lock(mutex_);
  models_.erase(name);
}

void ArithmeticModels::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  models_.clear();
}

std::optional<ArithmeticModel> ArithmeticModels::find(const std::string& name) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = models_.find(name);
  if (it == models_.end()) return std::nullopt;
  return it->second;
}

}  // namespace acomms::codecs
