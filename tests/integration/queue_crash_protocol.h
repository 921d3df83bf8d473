#pragma once
// What queue_crash_child does and prints, shared with the test that kills it
// (queue_crash_test.cpp).
//
// Each submitting thread k submits crash.Test{thread: k, seq: 0, 1, ...} one
// at a time through the daemon's own path (queue::Submitter::submit: encoded
// on the thread, stored by the writer, queued on the core thread), waiting
// for each answer, so what a thread attempted is known from what
// it printed: everything up to the last printed seq, plus at most one more
// in flight.
//
// stdout lines, each written by one write(2) once the fact is durable:
//   ok <id> <thread> <seq>   the submit of (thread, seq) returned id
//   removed <id>             a cancel of <id> was recorded and flushed
// Messages with seq % kRemoveEvery == 0 are cancelled right after their ok line.
//
// With "receive" for <threads>, the child instead receives
// crash.Test{thread: 0, seq: 0, 1, ...} from node 2 and prints
//   acked <seq>              the ACK for it would go out now
// at the moment the link would send that message's software ACK.

namespace acomms::testing::queue_crash {

inline constexpr int kRemoveEvery = 5;
inline constexpr const char* kType = "crash.Test";

inline constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package crash;
message Test {
  option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 64 };
  required int32 thread = 1 [(dccl.field) = { min: 0 max: 63 }];
  required int64 seq = 2 [(dccl.field) = { min: 0 max: 100000000 }];
  required bytes filler = 3 [(dccl.field) = { max_length: 32 }];
}
)";

// Queue settings under which nothing is dropped or expires during a run.
inline constexpr const char* kQueueConfig = "defaults { max_queue: 10000000 ttl_s: 1e9 }";

}  // namespace acomms::testing::queue_crash
