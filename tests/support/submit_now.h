#pragma once
// Submit a message to a QueueManager and have the answer at once.
//
// In a single-threaded test the test's thread is the core, and a
// MemoryJournal stores at once, so a Submitter whose core executor runs the
// work in place answers before submit() returns. Tests that drive queues
// directly (the link controller's, the in-process sim nodes) each spelled
// that out; here it is once.
//
// Thread-compatible: call on the thread that owns `queues`.

#include <google/protobuf/message.h>

#include "queue/queue_manager.h"
#include "queue/submitter.h"

namespace acomms::testing {

// The answer to submitting `message` (time-to-live 0: the type's default).
queue::SubmitResult submit_now(queue::QueueManager& queues, const google::protobuf::Message& message);

}  // namespace acomms::testing
