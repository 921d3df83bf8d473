// The compiled plan of one loaded DCCL type: what the schema loader hands
// the wire format.
//
// Loading resolves every field's codec, bit width and bounds once, so that
// encode and decode do no option or descriptor look-ups. A plan never
// changes once loaded (loaded types cannot be replaced), which is why the
// wire may read it from many threads without a lock.
#pragma once

#include "dccl/message_codec.h"
#include "dccl/type_info.h"

namespace google::protobuf {
class Message;
}  // namespace google::protobuf

namespace acomms::dccl {

struct TypePlan {
  TypeInfo info;
  MessageBody head;  // the in_head fields, after the id
  MessageBody body;
  // The empty message decode() copies; owned by the loader's message factory.
  const google::protobuf::Message* prototype = nullptr;
};

}  // namespace acomms::dccl
