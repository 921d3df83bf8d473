// Field codecs from plugins, found by name and configured per Codec.
//
// The problem: the daemon and acommsctl must offer every codec under
// plugins/codecs without including a plugin's header or keeping a list to
// edit, and a codec with settings of its own (the arithmetic codec's models)
// must take them from the Codec it serves, so that two Codecs in one process
// can hold different settings under the same names.
//
// The decision: a plugin adds itself before main() with a static
// PluginCodecRegistrar in its .cpp (its library is linked whole, so the
// linker keeps that object). An application sets up each dccl::Codec with
// install_plugin_codecs(codec.registry(), &settings): every plugin registers
// its field codecs into that one registry, configured from `settings`, the
// application's DCCL settings message (acommsd: acomms.v1.DcclConfig). A
// plugin reads its own field of that message by name, with reflection
// (the arithmetic codec reads "arithmetic_models"), so neither this layer
// nor the daemon knows any plugin's types.
//
// Invariants: plugins are added only during static initialisation; after
// that the list is read only, so installs may run on any thread. What a
// plugin takes from `settings` is copied into the registry it installs
// into and shared with nothing else.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "dccl/registry.h"

namespace google::protobuf {
class Message;
}  // namespace google::protobuf

namespace acomms::dccl {

// Registers a plugin's field codecs in `registry`, configured from
// `settings` (nullptr: none, the plugin's defaults). Throws Error (kSchema)
// "<field>: <problem>" naming the settings field it could not use.
using PluginCodecInstall =
    std::function<void(CodecRegistry& registry, const google::protobuf::Message* settings)>;

// Adds plugin `name` to the codecs linked into this program. Define one
// as a static object in the plugin's .cpp.
class PluginCodecRegistrar {
 public:
  PluginCodecRegistrar(const std::string& name, PluginCodecInstall install);
};

// The plugins linked into this program, by name (sorted).
std::vector<std::string> plugin_codec_names();

// Installs every linked plugin's codecs into `registry`, each configured
// from `settings`.
void install_plugin_codecs(CodecRegistry& registry, const google::protobuf::Message* settings = nullptr);

}  // namespace acomms::dccl
