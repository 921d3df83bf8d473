#pragma once
// A Subscribe stream held open by a test: what it delivers is collected on
// its own thread, so the test can wait for a condition on it. The stream
// ends when the daemon stops or dies; what it collected stays readable.
#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "acomms/v1/acomms.grpc.pb.h"
#include "daemon_harness.h"

namespace acomms::testing {

class StreamSubscriber {
 public:
  // `after`: replay the store's messages after that seq first (Subscribe's
  // `after`); unset: live messages only.
  StreamSubscriber(const std::string& socket, const std::string& type, std::optional<int64_t> after = std::nullopt)
      : stub_(api(socket)) {
    v1::SubscribeRequest request;
    request.add_types(type);
    if (after) request.set_after(*after);
    reader_ = stub_->Subscribe(&context_, request);
    // The server sends headers once subscribed: nothing published after
    // this can be missed.
    reader_->WaitForInitialMetadata();
    thread_ = std::thread([this] {
      v1::ReceivedMessage message;
      while (reader_->Read(&message)) {
        std::lock_guard lock(mutex_);
        received_.push_back(message);
      }
      end_ = reader_->Finish();
    });
  }
  ~StreamSubscriber() {
    context_.TryCancel();
    thread_.join();
  }
  StreamSubscriber(const StreamSubscriber&) = delete;
  StreamSubscriber& operator=(const StreamSubscriber&) = delete;

  std::vector<v1::ReceivedMessage> received() {
    std::lock_guard lock(mutex_);
    return received_;
  }
  // Waits until `done(received)` holds or `timeout` passes.
  template <typename Done>
  bool wait_for(Done done, std::chrono::seconds timeout) {
    return wait_until([&] { return done(received()); }, timeout, std::chrono::milliseconds(100));
  }

 private:
  std::unique_ptr<v1::Acomms::Stub> stub_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReader<v1::ReceivedMessage>> reader_;
  std::thread thread_;
  std::mutex mutex_;
  std::vector<v1::ReceivedMessage> received_;
  grpc::Status end_;
};

}  // namespace acomms::testing
