// What the QueueManager tests share: a codec, a simulated clock, a
// MemoryJournal and the manager under test with its Submitter, with helpers
// to build messages, submit them as a client would, move the clock and
// count logged events. Each test file loads its own schema and builds the
// manager its own way, then install()s it.
//
// The test's thread is the core thread. Work the Submitter posts to the
// core runs at once, unless a test holds it (hold_core()) to play messages
// being stored while others are queued, then runs it (run_core()).
#pragma once

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/clock.h"
#include "dccl/codec.h"
#include "queue/memory_journal.h"
#include "queue/queue_manager.h"
#include "queue/submitter.h"

namespace acomms::queue::testing {

inline constexpr double kStart = 1'700'000'000;  // the simulated clock's start
inline constexpr int32_t kOwnId = 1;             // this node's modem id

class QueueManagerFixture : public ::testing::Test {
 protected:
  // A message of `type` from text format (the test fails on bad text).
  std::unique_ptr<google::protobuf::Message> message(const std::string& type, const std::string& text) {
    auto m = codec_.new_message(type);
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, m.get())) << text;
    return m;
  }

  // Its DCCL encoding.
  std::string encode(const std::string& type, const std::string& text) { return codec_.encode(*message(type, text)); }

  // Makes `manager` the one under test, with a Submitter that posts to
  // this thread.
  QueueManager& install(std::unique_ptr<QueueManager> manager) {
    submitter_.reset();
    manager_ = std::move(manager);
    submitter_ = std::make_unique<Submitter>(*manager_, [this](std::function<void()> work) {
      if (holding_core_) {
        held_core_work_.push_back(std::move(work));
      } else {
        work();
      }
    });
    return *manager_;
  }

  // Where a submit's result lands once it is answered.
  using Answer = std::shared_ptr<std::optional<SubmitResult>>;

  // Submits as a client would (Submitter::submit). Answered at once, unless
  // the core's part is held.
  Answer submit_async(const std::string& type, const std::string& text, double ttl_s = 0) {
    auto answer = std::make_shared<std::optional<SubmitResult>>();
    submitter_->submit(*message(type, text), ttl_s, [answer](SubmitResult r) {
      EXPECT_FALSE(answer->has_value()) << "answered twice";
      *answer = std::move(r);
    });
    return answer;
  }

  // The same, nothing held: its result.
  SubmitResult submit_result(const std::string& type, const std::string& text, double ttl_s = 0) {
    Answer answer = submit_async(type, text, ttl_s);
    EXPECT_TRUE(answer->has_value()) << "not answered";
    return answer->value_or(SubmitResult{SubmitResult::Error::kStoreUnavailable, 0, "not answered"});
  }

  // The same, expecting it to be queued: its message id.
  int64_t submit(const std::string& type, const std::string& text, double ttl_s = 0) {
    SubmitResult result = submit_result(type, text, ttl_s);
    EXPECT_TRUE(result.ok()) << result.text;
    EXPECT_GT(result.message_id, 0);
    return result.message_id;
  }

  // From now on the core's part of a submit waits for run_core().
  void hold_core() { holding_core_ = true; }
  // Runs the held core work in order, and stops holding.
  void run_core() {
    holding_core_ = false;
    std::vector<std::function<void()>> work = std::move(held_core_work_);
    held_core_work_.clear();
    for (auto& w : work) w();
  }

  void at(double seconds_after_start) {
    clock_.set(core::Clock::time_point(std::chrono::duration_cast<core::Clock::time_point::duration>(
        std::chrono::duration<double>(kStart + seconds_after_start))));
  }

  // Events of `kind` in the journal so far.
  int count(QueueEventKind kind) {
    int n = 0;
    for (const auto& e : journal_.events()) n += e.kind == kind;
    return n;
  }

  std::filesystem::path dir_;
  dccl::Codec codec_;
  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(static_cast<int64_t>(kStart)))};
  MemoryJournal journal_;
  std::unique_ptr<QueueManager> manager_;
  std::unique_ptr<Submitter> submitter_;  // over manager_, see install()
  bool holding_core_ = false;
  std::vector<std::function<void()>> held_core_work_;
};

}  // namespace acomms::queue::testing
