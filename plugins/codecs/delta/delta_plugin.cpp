// "acomms.delta" as a plugin: installed into every Codec the application
// sets up with dccl::install_plugin_codecs(). It has no settings: its
// options are per field, in the schema ((acomms.codecs.delta).max_delta).

#include "delta/delta_codec.h"
#include "dccl/plugin_codecs.h"

namespace acomms::codecs {
namespace {

const dccl::PluginCodecRegistrar registrar(
    kDeltaCodecName, [](dccl::CodecRegistry& registry, const google::protobuf::Message* /*settings*/) {
      register_delta_codec(registry);
    });

}  // namespace
}  // namespace acomms::codecs
