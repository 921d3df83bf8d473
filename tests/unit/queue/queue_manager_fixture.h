// What the QueueManager tests share: a codec, a simulated clock, a
// MemoryJournal and the manager under test, with helpers to build messages,
// submit them as a client would, move the clock and count logged events.
// Each test file loads its own schema and builds the manager its own way.
#pragma once

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "core/clock.h"
#include "dccl/codec.h"
#include "queue/memory_journal.h"
#include "queue/queue_manager.h"

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

  // Submits as a client would: journal (any thread), then accept (core).
  int64_t submit(const std::string& type, const std::string& text, double ttl_s = 0) {
    QueuedMessage queued = manager_->journal_new(*message(type, text), ttl_s);
    int64_t id = queued.record.id;
    EXPECT_TRUE(manager_->accept(std::move(queued)));
    return id;
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
};

}  // namespace acomms::queue::testing
