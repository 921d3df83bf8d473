#pragma once
// Models for the arithmetic field codec, and the registry the codec finds
// them in by name.
//
// A model is not part of a .proto: as in the reference DCCL, the application
// gives it by name before loading the schemas whose fields say
// (dccl.field).(arithmetic).model = "<name>". Each dccl::Codec has its own
// models (two Codecs may hold different models of one name): the codec is
// registered with an ArithmeticModels, or installed from the application's
// settings (arithmetic_codec.h). Loading copies the model into the field's
// codec, so changing or re-adding a model later affects only schemas loaded
// after that.
//
//   auto models = std::make_shared<acomms::codecs::ArithmeticModels>();
//   acomms::codecs::ArithmeticModel m;
//   m.name = "depth";
//   m.value_bound = {0, 10, 50, 200, 6000};
//   m.frequency = {40, 30, 20, 10};
//   models->add(m);
//   acomms::codecs::register_arithmetic_codec(codec.registry(), models);
//
// Configuration can hold models as text (acomms/codecs/arithmetic_model.proto):
// ArithmeticModel::parse_text() and from_message() read that form.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace google::protobuf {
class Message;
}  // namespace google::protobuf

namespace acomms::codecs {

struct ArithmeticModel {
  std::string name;
  // Symbol i covers values [value_bound[i], value_bound[i + 1]) and has
  // frequency[i] (>= 1). value_bound is strictly increasing and has one
  // entry more than frequency.
  std::vector<uint32_t> frequency;
  std::vector<double> value_bound;
  // End of a list shorter than max_repeat; 0: lists must be full.
  uint32_t eof_frequency = 1;
  // Values outside [value_bound.front(), value_bound.back()); 0: they cannot
  // be sent.
  uint32_t out_of_range_frequency = 0;
  // Each coded symbol's frequency grows by one as a message is coded; every
  // message starts from the frequencies above.
  bool is_adaptive = false;

  // Throws dccl::Error (kind kSchema) "arithmetic model \"name\": <rule>"
  // if the model cannot be used.
  void validate() const;

  // Reads a message with the fields of acomms.codecs.v1.ArithmeticModel (by
  // name, so a dynamic message, a generated class or the reference DCCL's
  // dccl.arith.protobuf.ArithmeticModel all work). Does not validate.
  static ArithmeticModel from_message(const google::protobuf::Message& message);
  // Parses the text form, e.g. "name: 'm' value_bound: [0, 1, 2]
  // frequency: [5, 1]". Throws dccl::Error (kSchema) on a syntax error.
  static ArithmeticModel parse_text(std::string_view text);
};

// Models by name, for one Codec (or several that share them). Thread safe.
class ArithmeticModels {
 public:
  // Validates and adds model, replacing one of the same name.
  void add(const ArithmeticModel& model);
  void remove(const std::string& name);
  void clear();
  // A copy of the model called name, if any.
  std::optional<ArithmeticModel> find(const std::string& name) const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, ArithmeticModel> models_;
};

}  // namespace acomms::codecs
