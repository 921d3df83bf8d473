// The LinkController, which binds driver, MAC and queues: data requests filled from the
// queues, ACK frame indices mapped back to queue frames, received frames
// split and delivered, slots handed to the driver.

#include "link/link_controller.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <fstream>

#include "acomms/v1/link_figures.pb.h"
#include "mac/silent_mac.h"
#include "queue/memory_journal.h"
#include "submit_now.h"
#include "temp_dir.h"

namespace acomms::link {
namespace {

namespace pb = google::protobuf;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package lt;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

class FakeDriver final : public Driver {
 public:
  void start(DriverCallbacks callbacks) override { callbacks_ = std::move(callbacks); }
  void stop() override { stopped = true; }
  void do_work() override {}
  void initiate_transmission(const v1::ModemTransmission& t) override {
    initiated.push_back(t);
    v1::ModemTransmission out = t;
    out.set_max_frame_bytes(8);
    out.set_max_num_frames(2);
    callbacks_.on_data_request(&out);
    sent.push_back(out);
  }
  void receive(const v1::ModemTransmission& t) { callbacks_.on_receive(t); }
  // A poll for us heard: the driver asks for our data on its own.
  void answer_poll(const v1::ModemTransmission& response) {
    v1::ModemTransmission out = response;
    out.set_max_frame_bytes(8);
    out.set_max_num_frames(2);
    callbacks_.on_data_request(&out);
    sent.push_back(out);
  }

  DriverCallbacks callbacks_;
  std::vector<v1::ModemTransmission> initiated, sent;
  bool stopped = false;
};

class FakeMac final : public mac::Mac {
 public:
  void start(Transmit transmit) override { transmit_ = std::move(transmit); }
  void stop() override { stopped = true; }
  void set_cycle(const mac::Cycle& cycle) override { cycle_ = cycle; }
  const mac::Cycle& cycle() const override { return cycle_; }
  void on_receive(const v1::ModemTransmission&) override { ++heard; }
  void slot(int32_t src, int32_t dest) {
    v1::ModemTransmission t;
    t.set_src(src);
    t.set_dest(dest);
    transmit_(t);
  }
  // A slot of `seconds` at `rate` that began at `start` (seconds since 1970).
  void timed_slot(int32_t rate, double seconds, double start) {
    v1::ModemTransmission t;
    t.set_src(1);
    t.set_rate(rate);
    t.set_slot_seconds(seconds);
    t.set_time(start);
    transmit_(t);
  }
  Transmit transmit_;
  mac::Cycle cycle_;
  int heard = 0;
  bool stopped = false;
};

class LinkControllerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "lt.proto") << kProto;
    codec_.load((dir_ / "lt.proto").string());
    v1::QueueConfig config;
    pb::TextFormat::ParseFromString(
        R"(type { type: "lt.Status" roles { source_field: "src" destination_field: "dest" } })", &config);
    queues_ = std::make_unique<queue::QueueManager>(codec_, config, 1, clock_, journal_);
    link_ = std::make_unique<LinkController>(1, *queues_, mac_, driver_,
                                             [this](queue::ReceivedMessage m, const v1::ModemTransmission&) {
                                               delivered_.push_back(m.message->ShortDebugString());
                                             });
    link_->start();
  }

  int64_t submit(const std::string& text) {
    auto m = codec_.new_message("lt.Status");
    pb::TextFormat::ParseFromString(text, m.get());
    queue::SubmitResult result = acomms::testing::submit_now(*queues_, *m);
    EXPECT_TRUE(result.ok()) << result.text;
    return result.message_id;
  }

  LinkOptions options_for(double max_range_m) const {
    LinkOptions options;
    options.clock = &clock_;
    options.max_range_m = max_range_m;
    return options;
  }

  acomms::testing::TempDir dir_{"acomms-link"};
  dccl::Codec codec_;
  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  queue::MemoryJournal journal_;
  std::unique_ptr<queue::QueueManager> queues_;
  FakeDriver driver_;
  FakeMac mac_;
  std::unique_ptr<LinkController> link_;
  std::vector<std::string> delivered_;
};

TEST_F(LinkControllerTest, SlotBecomesATransmissionFilledFromTheQueues) {
  submit("dest: 2 value: 1");
  submit("dest: 2 value: 2");
  submit("dest: 2 value: 3");
  clock_.advance(std::chrono::seconds(5));
  mac_.slot(1, -1);
  ASSERT_EQ(driver_.initiated.size(), 1u);
  ASSERT_EQ(driver_.sent.size(), 1u);
  const v1::ModemTransmission& sent = driver_.sent[0];
  EXPECT_EQ(sent.dest(), 2);
  EXPECT_TRUE(sent.ack_requested());
  // 8-byte frames hold two 4-byte messages; two frames hold all three.
  ASSERT_EQ(sent.frame_size(), 2);
  EXPECT_EQ(codec_.decode(sent.frame(0)).size(), 2u);
  EXPECT_EQ(codec_.decode(sent.frame(1)).size(), 1u);
}

TEST_F(LinkControllerTest, AckIndicesClearTheirFramesOnly) {
  for (int v = 1; v <= 3; ++v) submit("dest: 2 value: " + std::to_string(v));
  clock_.advance(std::chrono::seconds(5));
  mac_.slot(1, -1);
  v1::ModemTransmission ack;
  ack.set_type(v1::ModemTransmission::ACK);
  ack.set_src(2);
  ack.set_dest(1);
  ack.add_acked_frame(1);  // only the second frame arrived
  driver_.receive(ack);
  EXPECT_EQ(queues_->find_queue("lt.Status")->size(), 2u);
  EXPECT_EQ(queues_->stats("lt.Status").acked, 1u);
  EXPECT_EQ(link_->stats().acks_received, 1u);
  // An ack meant for another node changes nothing.
  ack.set_dest(7);
  ack.set_acked_frame(0, 0);
  driver_.receive(ack);
  EXPECT_EQ(queues_->find_queue("lt.Status")->size(), 2u);
}

TEST_F(LinkControllerTest, EmptyQueuesStillSendAnEmptyBroadcast) {
  mac_.slot(1, -1);
  ASSERT_EQ(driver_.sent.size(), 1u);
  ASSERT_EQ(driver_.sent[0].frame_size(), 1);
  EXPECT_EQ(driver_.sent[0].frame(0), "");
  EXPECT_EQ(driver_.sent[0].dest(), 0);
  EXPECT_FALSE(driver_.sent[0].ack_requested());
}

TEST_F(LinkControllerTest, ReceivedFramesAreSplitAndDeliveredWhenForUs) {
  auto encode = [&](const std::string& text) {
    auto m = codec_.new_message("lt.Status");
    pb::TextFormat::ParseFromString(text, m.get());
    return codec_.encode(*m);
  };
  v1::ModemTransmission data;
  data.set_type(v1::ModemTransmission::DATA);
  data.set_src(3);
  data.set_dest(1);
  data.add_frame(encode("src: 3 dest: 1 value: 5") + encode("src: 3 dest: 9 value: 6"));
  data.add_frame(encode("src: 3 dest: 0 value: 7"));
  driver_.receive(data);
  EXPECT_EQ(delivered_, (std::vector<std::string>{"src: 3 dest: 1 value: 5", "src: 3 dest: 0 value: 7"}));
  EXPECT_EQ(mac_.heard, 1);
  EXPECT_EQ(link_->stats().messages_delivered, 2u);
}

// The store's commit hook reaches the driver, which holds software ACKs
// on it (link/driver_sequence.h).
TEST_F(LinkControllerTest, TheDriverGetsTheHookThatSaysWhenReceiptsAreDurable) {
  EXPECT_FALSE(driver_.callbacks_.after_receipt_durable) << "no hook given: the driver acknowledges at once";
  LinkOptions options = options_for(kDefaultMaxRangeM);
  int asked = 0;
  options.after_receipt_durable = [&asked](std::function<void()> then) {
    ++asked;
    then();
  };
  link_ = std::make_unique<LinkController>(
      1, *queues_, mac_, driver_, [](queue::ReceivedMessage, const v1::ModemTransmission&) {}, options);
  link_->start();
  ASSERT_TRUE(driver_.callbacks_.after_receipt_durable);
  bool ran = false;
  driver_.callbacks_.after_receipt_durable([&ran] { ran = true; });
  EXPECT_EQ(asked, 1);
  EXPECT_TRUE(ran);
}

// The fake driver's timing is driver.h's default (rate table + 10 %): at
// rate 5 with an ACK and the 2000 m guard, one frame needs 4.74 s of the
// slot, two 5.17 s.
TEST_F(LinkControllerTest, AsksTheQueuesOnlyForTheFramesThatFitTheSlot) {
  for (int v = 1; v <= 3; ++v) submit("dest: 2 value: " + std::to_string(v));
  mac_.timed_slot(5, 5.0, clock_.now_seconds());
  ASSERT_EQ(driver_.sent.size(), 1u);
  EXPECT_EQ(driver_.sent[0].max_num_frames(), 1u);
  ASSERT_EQ(driver_.sent[0].frame_size(), 1);
  EXPECT_EQ(codec_.decode(driver_.sent[0].frame(0)).size(), 2u);
  // A longer slot: the rate's (the driver's) two frames.
  mac_.timed_slot(5, 5.2, clock_.now_seconds());
  EXPECT_EQ(driver_.sent[1].max_num_frames(), 2u);
}

TEST_F(LinkControllerTest, ARequestLateInItsSlotGetsWhatIsLeftOfIt) {
  link_ = std::make_unique<LinkController>(
      1, *queues_, mac_, driver_, [](queue::ReceivedMessage, const v1::ModemTransmission&) {},
      options_for(kDefaultMaxRangeM));
  link_->start();
  for (int v = 1; v <= 3; ++v) submit("dest: 2 value: " + std::to_string(v));
  // 6 s slot, begun 1 s ago: 5 s are left, one frame's worth.
  mac_.timed_slot(5, 6.0, clock_.now_seconds() - 1.0);
  ASSERT_EQ(driver_.sent.size(), 1u);
  EXPECT_EQ(driver_.sent[0].frame_size(), 1);
  // With the guard for 100 m instead, the same 5 s hold both frames.
  link_ = std::make_unique<LinkController>(
      1, *queues_, mac_, driver_, [](queue::ReceivedMessage, const v1::ModemTransmission&) {},
      options_for(100));
  link_->start();
  mac_.timed_slot(5, 6.0, clock_.now_seconds() - 1.0);
  ASSERT_EQ(driver_.sent.size(), 2u);
  EXPECT_EQ(driver_.sent[1].frame_size(), 2);
}

TEST_F(LinkControllerTest, AnAnswerToAPollAlsoAllowsForThePollsTravel) {
  link_ = std::make_unique<LinkController>(
      1, *queues_, mac_, driver_, [](queue::ReceivedMessage, const v1::ModemTransmission&) {},
      options_for(kDefaultMaxRangeM));
  link_->start();
  for (int v = 1; v <= 3; ++v) submit("dest: 2 value: " + std::to_string(v));
  // Dated 1.2 s ago (the poll's arrival began, then the turnaround) in a
  // 7.5 s slot: 6.3 s left, less the poll's travel from up to 2000 m
  // (1.33 s): 4.97 s, one frame's worth.
  v1::ModemTransmission answer;
  answer.set_src(1);
  answer.set_rate(5);
  answer.set_slot_seconds(7.5);
  answer.set_time(clock_.now_seconds() - 1.2);
  driver_.answer_poll(answer);
  ASSERT_EQ(driver_.sent.size(), 1u);
  EXPECT_EQ(driver_.sent[0].max_num_frames(), 1u);
  EXPECT_EQ(driver_.sent[0].frame_size(), 1);
  // The MAC's own slot, dated alike, has its whole 6.3 s: two frames.
  mac_.timed_slot(5, 7.5, clock_.now_seconds() - 1.2);
  ASSERT_EQ(driver_.sent.size(), 2u);
  EXPECT_EQ(driver_.sent[1].max_num_frames(), 2u);
}

TEST_F(LinkControllerTest, ASlotTooShortForOneFrameSendsNothingAndKeepsTheQueue) {
  submit("dest: 2 value: 1");
  mac_.timed_slot(5, 4.0, clock_.now_seconds());
  ASSERT_EQ(driver_.sent.size(), 1u);
  EXPECT_EQ(driver_.sent[0].max_num_frames(), 0u);
  EXPECT_EQ(driver_.sent[0].frame_size(), 0);  // not even the empty broadcast
  EXPECT_EQ(queues_->find_queue("lt.Status")->size(), 1u);
  EXPECT_EQ(queues_->stats("lt.Status").sent, 0u);
}

TEST_F(LinkControllerTest, StopStopsMacAndDriver) {
  link_->stop();
  EXPECT_TRUE(mac_.stopped);
  EXPECT_TRUE(driver_.stopped);
}

// A satellite modem's driver holds a session when it decides (MAC "none")
// and asks for data then: no slot, so no slot budget cuts what it asked.
TEST_F(LinkControllerTest, ADataRequestTheDriverStartsUnderMacNoneGetsAllItAskedFor) {
  mac::SilentMac none;
  FakeDriver modem;
  LinkController link(1, *queues_, none, modem, [](queue::ReceivedMessage, const v1::ModemTransmission&) {},
                      options_for(2000));
  link.start();
  for (int i = 0; i < 6; ++i) submit("dest: 2 value: " + std::to_string(i));
  v1::ModemTransmission session;
  session.set_src(1);
  session.set_max_frame_bytes(8);
  session.set_max_num_frames(3);
  modem.callbacks_.on_data_request(&session);
  EXPECT_EQ(session.max_num_frames(), 3u);
  EXPECT_EQ(session.frame_size(), 3);
  EXPECT_EQ(queues_->stats("lt.Status").sent, 6u) << "two messages in each of three frames";
  link.stop();
}

TEST_F(LinkControllerTest, DisabledLinkStopsMacAndDriverAndEnabledStartsThemAgain) {
  EXPECT_TRUE(link_->set_enabled(false));
  EXPECT_TRUE(mac_.stopped);
  EXPECT_TRUE(driver_.stopped);
  EXPECT_FALSE(link_->enabled());
  EXPECT_FALSE(link_->set_enabled(false)) << "idempotent";
  mac_.stopped = driver_.stopped = false;
  mac_.transmit_ = nullptr;
  EXPECT_TRUE(link_->set_enabled(true));
  ASSERT_TRUE(mac_.transmit_) << "the MAC was not started again";
  submit("dest: 2 value: 1");
  mac_.slot(1, -1);
  ASSERT_EQ(driver_.sent.size(), 1u);
  EXPECT_EQ(driver_.sent[0].frame_size(), 1);
  EXPECT_EQ(queues_->stats("lt.Status").sent, 1u);
}

// With a choice of link: the controller offers only what its link may
// carry, and what it hears tells the choice that a node is reached.
TEST_F(LinkControllerTest, SendsARoutedMessageOnlyWhileItsLinkIsTheCarrier) {
  std::vector<v1::LinkConfig> links(2);
  links[0].set_name("acoustic");
  links[1].set_name("sat");
  v1::QueueConfig queue;
  pb::TextFormat::ParseFromString(
      R"(type { type: "lt.Status" route { dest: 2 link: "acoustic" link: "sat" fallback_after_s: 60 } })", &queue);
  LinkChoice choice = LinkChoice::from_config(links, queue, clock_.now_seconds());
  FakeMac mac;
  FakeDriver modem;
  LinkOptions options = options_for(0);
  options.choice = &choice;
  options.link_index = 0;
  LinkController acoustic(1, *queues_, mac, modem, [](queue::ReceivedMessage, const v1::ModemTransmission&) {},
                          options);
  acoustic.start();
  clock_.advance(std::chrono::seconds(61));
  submit("dest: 2 value: 1");
  mac.slot(1, -1);
  ASSERT_EQ(modem.sent.size(), 1u);
  EXPECT_EQ(modem.sent[0].frame(0), "") << "sent on acoustic after 61 s without hearing node 2";
  v1::ModemTransmission heard;
  heard.set_type(v1::ModemTransmission::DATA);
  heard.set_src(2);
  heard.set_dest(0);
  heard.add_frame("");
  modem.receive(heard);
  mac.slot(1, -1);
  ASSERT_EQ(modem.sent.size(), 2u);
  EXPECT_EQ(modem.sent[1].dest(), 2);
  EXPECT_NE(modem.sent[1].frame(0), "") << "node 2 heard on acoustic: acoustic carries again";
  acoustic.stop();
}

}  // namespace
}  // namespace acomms::link

namespace acomms::link {
namespace {

// What acommsctl link calibrate fits: one "packet" event per packet heard
// from another node with figures, decoded or lost, mini-packets as rate 0.
TEST_F(LinkControllerTest, EachPacketHeardWithFiguresIsAPacketEventDecodedOrLost) {
  auto packets = [this] {
    std::vector<queue::QueueEvent> out;
    for (const queue::QueueEvent& e : journal_.events()) {
      if (e.kind == queue::QueueEventKind::kPacket) out.push_back(e);
    }
    return out;
  };
  auto figures_of = [](const queue::QueueEvent& e) {
    v1::LinkFigures f;
    EXPECT_TRUE(e.link_figures && f.ParseFromString(*e.link_figures));
    return f;
  };
  v1::ModemTransmission data;
  data.set_type(v1::ModemTransmission::DATA);
  data.set_src(2);
  data.set_dest(1);
  data.set_rate(3);
  data.add_frame("");
  data.mutable_figures()->set_snr_in_db(11);
  data.mutable_figures()->set_predicted_snr_db(15);
  data.mutable_figures()->set_predicted_tl_db(60);
  driver_.receive(data);
  v1::ModemTransmission ack;  // a mini-packet, whatever rate it names
  ack.set_type(v1::ModemTransmission::ACK);
  ack.set_src(2);
  ack.set_dest(1);
  ack.set_rate(5);
  ack.mutable_figures()->set_predicted_snr_db(14);
  driver_.receive(ack);
  v1::ModemTransmission lost;
  lost.set_type(v1::ModemTransmission::DATA);
  lost.set_src(3);
  lost.set_dest(1);
  lost.set_rate(1);
  lost.mutable_figures()->set_predicted_snr_db(2);
  driver_.callbacks_.on_reception_failed(lost);
  v1::ModemTransmission plain = data;  // no figures: nothing to fit
  plain.clear_figures();
  driver_.receive(plain);
  v1::ModemTransmission own = data;  // our own: never a link
  own.set_src(1);
  driver_.receive(own);

  const std::vector<queue::QueueEvent> events = packets();
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].src, 2);
  EXPECT_EQ(events[0].dest, 1);
  const v1::LinkFigures first = figures_of(events[0]);
  EXPECT_TRUE(first.decoded());
  EXPECT_EQ(first.rate(), 3);
  EXPECT_EQ(first.transmission_src(), 2);
  EXPECT_DOUBLE_EQ(first.snr_in_db(), 11);
  EXPECT_DOUBLE_EQ(first.predicted_snr_db(), 15);
  EXPECT_DOUBLE_EQ(first.predicted_tl_db(), 60);
  const v1::LinkFigures second = figures_of(events[1]);
  EXPECT_TRUE(second.decoded());
  EXPECT_EQ(second.rate(), 0) << "mini-packets are FSK: rate 0's curve";
  EXPECT_EQ(events[2].src, 3);
  const v1::LinkFigures third = figures_of(events[2]);
  ASSERT_TRUE(third.has_decoded());
  EXPECT_FALSE(third.decoded());
  EXPECT_EQ(third.rate(), 1);
  EXPECT_FALSE(third.has_snr_in_db());
}

TEST_F(LinkControllerTest, APacketWhoseEveryFrameWasBadIsLoggedLost) {
  v1::ModemTransmission data;
  data.set_type(v1::ModemTransmission::DATA);
  data.set_src(2);
  data.set_dest(1);
  data.set_rate(1);
  data.add_frame("");
  data.mutable_figures()->set_frames(2);
  data.mutable_figures()->set_bad_frames(2);
  driver_.receive(data);
  std::vector<queue::QueueEvent> events = journal_.events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, queue::QueueEventKind::kPacket);
  v1::LinkFigures f;
  ASSERT_TRUE(f.ParseFromString(*events[0].link_figures));
  EXPECT_FALSE(f.decoded());
}

}  // namespace
}  // namespace acomms::link
