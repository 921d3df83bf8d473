#pragma once
// Every field codec shipped in plugins/codecs. The daemon and acommsctl call
// this on each dccl::Codec before loading schemas, so a .proto can name any
// of them in (dccl.field).codec.

#include "dccl/registry.h"

namespace acomms::codecs {

void register_plugin_codecs(dccl::CodecRegistry& registry);

}  // namespace acomms::codecs
