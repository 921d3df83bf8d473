#include "dccl/plugin_codecs.h"

#include <map>

namespace acomms::dccl {
namespace {

// Filled by the registrars during static initialisation: a function-local
// static, so it exists whichever translation unit registers first.
std::map<std::string, PluginCodecInstall>& plugins() {
  static std::map<std::string, PluginCodecInstall> by_name;
  return by_name;
}

}  // namespace

PluginCodecRegistrar::PluginCodecRegistrar(const std::string& name, PluginCodecInstall install) {
  plugins()[name] = std::move(install);
}

std::vector<std::string> plugin_codec_names() {
  std::vector<std::string> names;
  for (const auto& [name, install] : plugins()) names.push_back(name);
  return names;
}

void install_plugin_codecs(CodecRegistry& registry, const google::protobuf::Message* settings) {
  for (const auto& [name, install] : plugins()) install(registry, settings);
}

}  // namespace acomms::dccl
