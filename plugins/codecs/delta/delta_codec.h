#pragma once
// The delta-difference field codec ("acomms.delta"), after the Goby1 design:
// a repeated float/double field is sent as
//
//   count - min_repeat   ceil_log2(max_repeat - min_repeat + 1) bits
//   key = x[0]           the field's normal bounded encoding (required)
//   x_delta[i], i >= 1   nint((x[i] + max_delta - key) * 10^precision) + 1,
//                        0 when |x[i] - key| > max_delta
//
// so a series of N slowly varying samples costs one full-width sample plus
// N-1 narrow ones. The key used for the differences is the key as the
// receiver decodes it (quantised), so no error accumulates. Options: min,
// max, precision (or resolution), max_repeat, min_repeat, and
// (acomms.codecs.delta).max_delta from api/proto/acomms/codecs/delta.proto.

#include "dccl/registry.h"

namespace acomms::codecs {

inline constexpr const char* kDeltaCodecName = "acomms.delta";
inline constexpr const char* kDeltaOptionsExtension = "acomms.codecs.delta";

void register_delta_codec(dccl::CodecRegistry& registry);

}  // namespace acomms::codecs
