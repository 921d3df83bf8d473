#pragma once
// The one DCCL type the network tests send: a status with source and
// destination roles, small enough for any Micro-Modem rate.

namespace acomms::testing {

inline constexpr const char* kNetStatusProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package net;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 10 max_bytes: 32 };
  required int32 src = 1 [(dccl.field) = { min: 0 max: 127 }];
  required int32 dest = 2 [(dccl.field) = { min: 0 max: 127 }];
  required int32 battery = 3 [(dccl.field) = { min: 0 max: 100 }];
}
)";

}  // namespace acomms::testing
