#include "register_codecs.h"

#include "delta/delta_codec.h"

namespace acomms::codecs {

void register_plugin_codecs(dccl::CodecRegistry& registry) { register_delta_codec(registry); }

}  // namespace acomms::codecs
