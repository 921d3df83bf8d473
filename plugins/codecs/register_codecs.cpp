#include "register_codecs.h"

#include "arithmetic/arithmetic_codec.h"
#include "delta/delta_codec.h"

namespace acomms::codecs {

void register_plugin_codecs(dccl::CodecRegistry& registry) {
  register_delta_codec(registry);
  // Models come from ArithmeticModels::global(), filled by the application.
  register_arithmetic_codec(registry);
}

}  // namespace acomms::codecs
