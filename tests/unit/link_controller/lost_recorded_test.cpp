// What a link tells a telemetry gap it already recorded lost
// (LinkController::lost_recorded, node/unheard_packets.h, issue 32): the
// bad frames of packets to this node or broadcast, decoded or not, at
// least one per packet that did not decode; never packets overheard
// between other nodes (they are no part of this node's telemetry).
#include <gtest/gtest.h>

#include "link/link_controller.h"
#include "queue/memory_journal.h"

namespace acomms::link {
namespace {

class ListeningDriver final : public Driver {
 public:
  void start(DriverCallbacks callbacks) override { callbacks_ = std::move(callbacks); }
  void stop() override {}
  void do_work() override {}
  void initiate_transmission(const v1::ModemTransmission&) override {}
  DriverCallbacks callbacks_;
};

class IdleMac final : public mac::Mac {
 public:
  void start(Transmit) override {}
  void stop() override {}
  void set_cycle(const mac::Cycle& cycle) override { cycle_ = cycle; }
  const mac::Cycle& cycle() const override { return cycle_; }
  void on_receive(const v1::ModemTransmission&) override {}
  mac::Cycle cycle_;
};

v1::ModemTransmission packet(int32_t src, int32_t dest, uint32_t frames, uint32_t bad_frames) {
  v1::ModemTransmission t;
  t.set_type(v1::ModemTransmission::DATA);
  t.set_src(src);
  t.set_dest(dest);
  t.set_rate(1);
  if (frames > bad_frames) t.add_frame("");
  t.mutable_figures()->set_frames(frames);
  t.mutable_figures()->set_bad_frames(bad_frames);
  t.mutable_figures()->set_snr_in_db(10);
  return t;
}

TEST(LostRecorded, CountsTheBadFramesOfPacketsToThisNodeOrBroadcastOnly) {
  dccl::Codec codec;
  core::SimulatedClock clock{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  queue::MemoryJournal journal;
  queue::QueueManager queues(codec, v1::QueueConfig(), 1, clock, journal);
  ListeningDriver driver;
  IdleMac mac;
  LinkOptions options;
  options.clock = &clock;
  LinkController link(1, queues, mac, driver, [](queue::ReceivedMessage, const v1::ModemTransmission&) {}, options);
  link.start();

  // A PSK packet to us whose first frame failed and second decoded: the
  // packet decoded, the first frame's telemetry is lost and told.
  driver.callbacks_.on_receive(packet(2, 1, 2, 1));
  EXPECT_EQ(link.lost_recorded(2), 1u);
  // A poll's answer that never came (no figures): one.
  v1::ModemTransmission timeout;
  timeout.set_type(v1::ModemTransmission::DATA);
  timeout.set_src(2);
  timeout.set_dest(1);
  driver.callbacks_.on_reception_failed(timeout);
  EXPECT_EQ(link.lost_recorded(2), 2u);
  // A broadcast whose three frames all failed: three.
  driver.callbacks_.on_receive(packet(2, 0, 3, 3));
  EXPECT_EQ(link.lost_recorded(2), 5u);
  // Overheard, 2 to 3: damaged, lost or partly bad, none of it ours.
  driver.callbacks_.on_reception_failed(packet(2, 3, 1, 1));
  driver.callbacks_.on_receive(packet(2, 3, 2, 1));
  driver.callbacks_.on_receive(packet(2, 3, 2, 2));
  EXPECT_EQ(link.lost_recorded(2), 5u);
  // A clean packet to us adds nothing; another sender's are its own.
  driver.callbacks_.on_receive(packet(2, 1, 2, 0));
  EXPECT_EQ(link.lost_recorded(2), 5u);
  EXPECT_EQ(link.lost_recorded(3), 0u);
  link.stop();
}

}  // namespace
}  // namespace acomms::link
