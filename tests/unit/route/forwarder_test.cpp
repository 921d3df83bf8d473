// The Forwarder's config checks and its custody queues' policies
// (route/forwarder.h); forwarding itself runs in the gateway network test
// (tests/system/gateway_network_test.cpp).
#include "route/forwarder.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>

#include "core/clock.h"
#include "queue/memory_journal.h"
#include "temp_dir.h"

namespace acomms::route {
namespace {

class ForwarderTest : public ::testing::Test {
 protected:
  ForwarderTest() {
    std::ofstream(dir_ / "t.proto") << R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package t;
message Big {
  option (dccl.msg) = { codec_version: 4 id: 300 max_bytes: 8 };
  required int32 x = 1 [(dccl.field) = { min: 0 max: 10 }];
}
)";
    codec_.load((dir_ / "t.proto").string());
    queues_ = std::make_unique<queue::QueueManager>(codec_, v1::QueueConfig(), 1, clock_, journal_);
  }
  Forwarder make(const std::string& text, int32_t own_id = 1) {
    v1::RoutingConfig config;
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &config)) << text;
    return Forwarder(config, own_id, {"acoustic"}, codec_, *queues_, clock_, 1800, [](std::function<void()> f) { f(); });
  }
  void expect_refused(const std::string& text, const std::string& names, int32_t own_id = 1) {
    try {
      make(text, own_id);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(names), std::string::npos) << e.what();
    }
  }

  testing::TempDir dir_{"acomms-forwarder"};
  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(1'748'772'000))};
  dccl::Codec codec_;
  queue::MemoryJournal journal_;
  std::unique_ptr<queue::QueueManager> queues_;
};

TEST_F(ForwarderTest, ConfigMistakesAreRefusedNamingTheField) {
  expect_refused("envelope_id: 300", "routing.envelope_id 300 is the DCCL id of t.Big");
  expect_refused("envelope_id: 100", "routing.envelope_id 100 is not in 128..32767");
  expect_refused("hop_limit: 0", "routing.hop_limit 0");
  expect_refused("hop_limit: 16", "routing.hop_limit 16");
  expect_refused("max_custody: 0", "routing.max_custody");
  expect_refused("", "does not fit the envelope", 70000);
  expect_refused("route { dest: 3 next_hop: 2 link: \"sat\" }", "routing.route[0].link \"sat\"");
}

TEST_F(ForwarderTest, ATypeLoadedLaterWithTheEnvelopeIdIsRefusedNamingIt) {
  Forwarder forwarder = make("envelope_id: 400");
  std::ofstream(dir_ / "late.proto") << R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package late;
message Clash {
  option (dccl.msg) = { codec_version: 4 id: 400 max_bytes: 8 };
  required int32 x = 1 [(dccl.field) = { min: 0 max: 10 }];
}
)";
  try {
    codec_.load((dir_ / "late.proto").string());
    ADD_FAILURE() << "late.Clash loaded with the envelope's id";
  } catch (const dccl::Error& e) {
    EXPECT_NE(std::string(e.what()).find("late.Clash: DCCL id 400 is reserved for routing.envelope_id"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(codec_.find_type("late.Clash"), nullptr);
}

TEST_F(ForwarderTest, CustodyQueuesTakeTheirPriorityFromTheirName) {
  Forwarder forwarder = make("max_custody: 7");
  auto policy = forwarder.custody_policy("acomms.route.Custody.v15");
  ASSERT_TRUE(policy);
  EXPECT_DOUBLE_EQ(policy->value_base, 1.5);
  // Twice routing.max_custody: room, at restore, for custody taken over
  // the bound before custody receipts; take_custody now refuses at the
  // bound on every link (a modem-ACK link answers with a receipt).
  EXPECT_EQ(policy->max_queue, 14u);
  EXPECT_DOUBLE_EQ(policy->ttl_s, 1800);
  EXPECT_FALSE(policy->newest_first);
  EXPECT_EQ(policy->on_full, queue::QueuePolicy::OnFull::kRefuseNew);
  EXPECT_FALSE(forwarder.custody_policy("t.Big"));
  EXPECT_FALSE(forwarder.custody_policy("acomms.route.Custody.v"));
  EXPECT_FALSE(forwarder.custody_policy("acomms.route.Custody.v256"));
  EXPECT_FALSE(forwarder.custody_policy("acomms.route.Custody.v1x"));
}

}  // namespace
}  // namespace acomms::route
