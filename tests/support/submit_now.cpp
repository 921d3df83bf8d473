#include "submit_now.h"

#include <functional>

namespace acomms::testing {

queue::SubmitResult submit_now(queue::QueueManager& queues, const google::protobuf::Message& message) {
  queue::Submitter submitter(queues, [](std::function<void()> work) { work(); });
  queue::SubmitResult result;
  submitter.submit(message, 0, [&result](queue::SubmitResult r) { result = std::move(r); });
  return result;
}

}  // namespace acomms::testing
