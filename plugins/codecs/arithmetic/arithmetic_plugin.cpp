// "dccl.arithmetic" as a plugin: installed into every Codec the application
// sets up with dccl::install_plugin_codecs(), with that Codec's own models,
// read from the settings' arithmetic_models field (acommsd's
// dccl.arithmetic_models). Nothing here is process-wide but the registrar,
// so two Codecs never see each other's models.

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <memory>
#include <string>

#include "arithmetic/arithmetic_codec.h"
#include "dccl/error.h"
#include "dccl/plugin_codecs.h"

namespace acomms::codecs {
namespace {

namespace pb = google::protobuf;

std::shared_ptr<ArithmeticModels> models_from(const pb::Message* settings) {
  auto models = std::make_shared<ArithmeticModels>();
  if (settings == nullptr) return models;
  const pb::FieldDescriptor* field = settings->GetDescriptor()->FindFieldByName(kArithmeticModelsSetting);
  // Settings without the field (another application's) simply give no models.
  if (field == nullptr || !field->is_repeated() || field->cpp_type() != pb::FieldDescriptor::CPPTYPE_MESSAGE) {
    return models;
  }
  const pb::Reflection* reflection = settings->GetReflection();
  for (int i = 0; i < reflection->FieldSize(*settings, field); ++i) {
    try {
      models->add(ArithmeticModel::from_message(reflection->GetRepeatedMessage(*settings, field, i)));
    } catch (const dccl::Error& e) {
      throw dccl::schema_error(std::string(kArithmeticModelsSetting) + ": " + e.what());
    }
  }
  return models;
}

const dccl::PluginCodecRegistrar registrar(kArithmeticCodecName, install_arithmetic_codec);

}  // namespace

void install_arithmetic_codec(dccl::CodecRegistry& registry, const pb::Message* settings) {
  register_arithmetic_codec(registry, models_from(settings));
}

}  // namespace acomms::codecs
