#pragma once
// DCCL's arithmetic field codec ("dccl.arithmetic"): the values of a field
// are mapped to the symbols of a named model (see arithmetic_model.h) and
// arithmetic coded, so likely values cost a fraction of a bit.
//
//   import "dccl/arithmetic/protobuf/arithmetic_extensions.proto";
//   repeated double depth = 3 [(dccl.field).codec = "dccl.arithmetic",
//                              (dccl.field).(arithmetic).model = "depth",
//                              (dccl.field).max_repeat = 10];
//
// Wire format (checked against the reference vector in shared/spec):
// - Coding alphabet, in cumulative order: out-of-range, end-of-field (EOF),
//   then the model's value symbols in value_bound order.
// - A value v is symbol i when value_bound[i] <= v < value_bound[i + 1];
//   anything else (NaN included) is out of range. Comparisons are made in the
//   field's type (float fields compare with the bounds rounded to float);
//   integer, enum (by number) and bool (0/1) fields work as well as float
//   and double. Symbol i decodes as value_bound[i] (rounded up to an integer
//   for integer types, clamped to the type's range).
// - The elements are coded in order, then EOF unless max_repeat elements
//   were coded (a full list needs no terminator). Elements past max_repeat
//   are dropped (an error in strict mode). A singular field is a list of at
//   most one: its value, or EOF when an optional field is unset.
// - An out-of-range value is sent as the out-of-range symbol, which decodes
//   as NaN for float/double; for other types it decodes as "no value" (an
//   unset singular field, or no element in a repeated one). If the model's
//   out_of_range_frequency is 0 the value cannot be sent: strict mode throws;
//   otherwise the list ends there with EOF, as the reference does.
// - If eof_frequency is 0 a list shorter than max_repeat cannot be sent and
//   encode() throws in either mode.
// - Bits come from dccl::arith::Encoder (arithmetic_coder.h): the fewest that pin
//   the final interval, so the field's end is known without a length.
// - Adaptive models restart from the registered frequencies for every
//   message (and every field), so each message decodes on its own.
//
// Size bounds reported to load-time validation: min 0 (a certain symbol
// costs no bits); max 2 + the information content of the costliest list,
// using the least likely symbol at every step, each probability lowered by
// 2^-30 for integer rounding (and, for adaptive models, by the largest total
// the list can reach), plus one bit of margin.

#include <memory>

#include "arithmetic/arithmetic_model.h"
#include "dccl/registry.h"

namespace google::protobuf {
class Message;
}  // namespace google::protobuf

namespace acomms::codecs {

inline constexpr const char* kArithmeticCodecName = "dccl.arithmetic";
// The (dccl.field) extension holding ArithmeticOptions (global scope, as in
// the reference's arithmetic_extensions.proto).
inline constexpr const char* kArithmeticOptionsExtension = "arithmetic";

// The field of the application's DCCL settings that holds a Codec's models
// (acommsd: dccl.arithmetic_models, a repeated acomms.codecs.v1.ArithmeticModel).
inline constexpr const char* kArithmeticModelsSetting = "arithmetic_models";

// Registers "dccl.arithmetic", finding models in `models` when schemas load.
void register_arithmetic_codec(dccl::CodecRegistry& registry, std::shared_ptr<const ArithmeticModels> models);
// Registers "dccl.arithmetic" with the models listed in `settings`'
// arithmetic_models field (none when settings is null or has no such
// field): how dccl::install_plugin_codecs() sets the codec up for one Codec.
// Throws dccl::Error (kSchema) "arithmetic_models: arithmetic model "x": <rule>".
void install_arithmetic_codec(dccl::CodecRegistry& registry, const google::protobuf::Message* settings);

}  // namespace acomms::codecs
