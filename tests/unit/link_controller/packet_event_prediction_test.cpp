// The packet events of a link (issue 32): each names the node's link that
// heard it, and takes the model's prediction from LinkOptions::predict
// (node/link_prediction.h for a real modem) when the driver gave none, for
// decoded and lost packets alike; a driver's own prediction (the
// simulator's) is kept.
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <fstream>

#include "acomms/v1/link_figures.pb.h"
#include "link/link_controller.h"
#include "queue/memory_journal.h"
#include "temp_dir.h"

namespace acomms::link {
namespace {

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package pp;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 value = 1 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

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

TEST(PacketEventPrediction, EachEventNamesItsLinkAndCarriesThePredictionWhenTheDriverHasNone) {
  acomms::testing::TempDir dir{"acomms-packet-prediction"};
  std::ofstream(dir.path() / "pp.proto") << kProto;
  dccl::Codec codec;
  codec.load((dir.path() / "pp.proto").string());
  core::SimulatedClock clock{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  queue::MemoryJournal journal;
  queue::QueueManager queues(codec, v1::QueueConfig(), 1, clock, journal);
  std::vector<v1::LinkConfig> links(2);
  links[0].set_name("acoustic");
  links[1].set_name("sat");
  LinkChoice choice = LinkChoice::from_config(links, v1::QueueConfig(), clock.now_seconds());
  ListeningDriver driver;
  IdleMac mac;
  LinkOptions options;
  options.clock = &clock;
  options.choice = &choice;
  options.link_index = 1;
  std::vector<int32_t> asked;
  options.predict = [&](const v1::ModemTransmission& heard, v1::LinkFigures& figures) {
    asked.push_back(heard.src());
    figures.set_predicted_tl_db(60 + heard.src());
    figures.set_predicted_snr_db(20 - heard.src());
  };
  LinkController link(1, queues, mac, driver, [](queue::ReceivedMessage, const v1::ModemTransmission&) {}, options);
  link.start();

  v1::ModemTransmission decoded;  // a Micro-Modem's: measured, not predicted
  decoded.set_type(v1::ModemTransmission::DATA);
  decoded.set_src(2);
  decoded.set_dest(1);
  decoded.set_rate(1);
  decoded.add_frame("");
  decoded.mutable_figures()->set_snr_in_db(12);
  driver.callbacks_.on_receive(decoded);
  v1::ModemTransmission lost;  // a poll's answer that never came: no figures at all
  lost.set_type(v1::ModemTransmission::DATA);
  lost.set_src(3);
  lost.set_dest(1);
  lost.set_rate(1);
  driver.callbacks_.on_reception_failed(lost);
  v1::ModemTransmission simulated = decoded;  // the simulator's: its own prediction stays
  simulated.set_src(4);
  simulated.mutable_figures()->set_predicted_snr_db(7);
  driver.callbacks_.on_receive(simulated);

  std::vector<v1::LinkFigures> packets;
  for (const queue::QueueEvent& e : journal.events()) {
    if (e.kind != queue::QueueEventKind::kPacket) continue;
    v1::LinkFigures f;
    ASSERT_TRUE(e.link_figures && f.ParseFromString(*e.link_figures));
    packets.push_back(f);
  }
  ASSERT_EQ(packets.size(), 3u);
  for (const v1::LinkFigures& f : packets) EXPECT_EQ(f.link(), "sat");
  EXPECT_TRUE(packets[0].decoded());
  EXPECT_DOUBLE_EQ(packets[0].snr_in_db(), 12);
  EXPECT_DOUBLE_EQ(packets[0].predicted_tl_db(), 62);
  EXPECT_DOUBLE_EQ(packets[0].predicted_snr_db(), 18);
  EXPECT_FALSE(packets[1].decoded());
  EXPECT_EQ(packets[1].transmission_src(), 3);
  EXPECT_DOUBLE_EQ(packets[1].predicted_snr_db(), 17);
  EXPECT_DOUBLE_EQ(packets[2].predicted_snr_db(), 7);
  EXPECT_FALSE(packets[2].has_predicted_tl_db());
  EXPECT_EQ(asked, (std::vector<int32_t>{2, 3})) << "not asked where the driver predicted";
  link.stop();
}

}  // namespace
}  // namespace acomms::link
