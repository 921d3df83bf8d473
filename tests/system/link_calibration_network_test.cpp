// The model meets the sea, closed on itself: a two-node sim network whose
// physics has a planted excess loss and reception curve (what a real site
// would add to the model), run on the simulated clock while one node opens
// the range; the receiving node's own event log ("packet" events, as the
// Events RPC returns them) is then calibrated, and the planted figures must
// come back: excess loss within ±1.5 dB, the 50% point within ±2 dB, and a
// physics block the simulator's config takes as is. Too few packets are
// refused with the reason.
// Environment: 100 m of water at 2 kHz over sand (model runs take
// milliseconds).
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "eval/link_calibration.h"
#include "gram/bellhop_import.h"
#include "gram/tl_lookup.h"
#include "net_status_proto.h"
#include "queue/queue_event.h"
#include "sim/tl_grid_source.h"
#include "sim_node.h"
#include "temp_dir.h"

namespace acomms {
namespace {

using namespace std::chrono_literals;

constexpr const char* kEnv = R"('calibration test: 100 m, thermocline 10-30 m, 2 kHz'
2000
1
'CVW'
0 0.0 100
  0.0 1536.0 /
 10.0 1535.6 /
 30.0 1511.8 /
100.0 1511.0 /
'A' 0.0
100.0 1650.0 0.0 1.9 0.8 0.0 /
1
30 /
1
50 /
1
1 /
'I'
0
-80 80 /
0 101 2.1
)";

// The site, planted: what calibrate must find.
constexpr double kExcessLossDb = 6.0, kSnr50Db = 10.0, kSlopePerDb = 0.8;
constexpr double kBuoyDepth = 20, kVehicleDepth = 40;
constexpr double kNearM = 100, kFarM = 1900, kThresholdRangeM = 1000;
constexpr double kMaxRange = 2000, kRangeStep = 20, kDepthStep = 5;

// The noise that puts the planted 50% point at kThresholdRangeM: the TL
// there from the model itself, as the buoy's grid (the buoy as source).
double noise_for_threshold(const std::string& env_file) {
  gram::Environment env = gram::import_bellhop_env_file(env_file).environment;
  env.clear_receiver_depth_m();
  env.clear_receiver_range_m();
  for (int i = 0; i <= 20; ++i) env.add_receiver_depth_m(i * kDepthStep);
  for (int i = 0; i <= 100; ++i) env.add_receiver_range_m(i * kRangeStep);
  env.set_source_depth_m(kBuoyDepth);
  const double tl = gram::tl_at(gram::compute_transmission_loss(env, {1}), kThresholdRangeM, kVehicleDepth);
  return gram::kDefaultSourceLevelDb - tl - kExcessLossDb - kSnr50Db;
}

struct Network {
  explicit Network(const testing::TempDir& dir) {
    std::ofstream(dir / "net.proto") << testing::kNetStatusProto;
    env_file = (dir / "site.env").string();
    std::ofstream(env_file) << kEnv;
    const double noise = noise_for_threshold(env_file);
    auto physics = [&](double depth) {
      return [this, noise, depth](v1::DriverConfig& c) {
        c.mutable_sim()->mutable_position()->set_z(-depth);
        auto* p = c.mutable_sim()->mutable_physics();
        p->set_env_file(env_file);
        p->set_noise_level_db(noise);
        p->set_max_range_m(kMaxRange);
        p->set_range_step_m(kRangeStep);
        p->set_depth_step_m(kDepthStep);
        p->set_excess_loss_db(kExcessLossDb);
        auto* curve = p->add_reception();
        curve->set_rate(0);
        curve->set_snr50_db(kSnr50Db);
        curve->set_slope_per_db(kSlopePerDb);
      };
    };
    // Node 1 (the vehicle) has the only slot and sends one message in each;
    // no ACKs, so every packet in the water is one DATA from 1 to 2.
    auto setup = [&](int32_t id, double x, double depth) {
      return testing::SimNodeSetup{
          .id = id,
          .x = x,
          .proto = (dir / "net.proto").string(),
          .queue_config = R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } )"
                          R"(policy { ack: false } })",
          .mac_config = R"(name: "fixed" slot { src: 1 rate: 0 seconds: 10 })",
          .link_options_from_mac = false,
          .wrap_driver = nullptr,
          .configure_driver = physics(depth)};
    };
    auto ignore = [](queue::ReceivedMessage, const v1::ModemTransmission&) {};
    vehicle = std::make_unique<testing::SimNode>(setup(1, kNearM, kVehicleDepth), scheduler, channel, ignore);
    buoy = std::make_unique<testing::SimNode>(setup(2, 0, kBuoyDepth), scheduler, channel, ignore);
    // The model off the link's timeline: run at once (milliseconds on this
    // small grid), answered on the simulated clock's next turn.
    for (testing::SimNode* node : {vehicle.get(), buoy.get()}) {
      node->driver->set_tl_grid_source(std::make_shared<drivers::ExecutorTlGridSource>(
          [](std::function<void()> task) { task(); },
          [this](std::function<void()> task) { scheduler.after(0s, std::move(task)); }));
    }
    vehicle->link->start();
    buoy->link->start();
  }

  // `packets` slots, the vehicle opening the range from kNearM to kFarM.
  void run(int packets) {
    for (int i = 0; i < packets; ++i) {
      const double x = kNearM + (kFarM - kNearM) * i / std::max(1, packets - 1);
      vehicle->driver->set_position({x, 0, -kVehicleDepth});
      vehicle->submit("net.Status", "dest: 2 battery: " + std::to_string(i % 100));
      scheduler.run_for(10s);
    }
  }

  // The buoy's event log as the Events RPC gives it (service/event_rpcs.cpp).
  std::vector<v1::Event> buoy_events() const {
    std::vector<v1::Event> out;
    for (const queue::QueueEvent& e : buoy->journal.events()) {
      v1::Event& event = out.emplace_back();
      event.set_time(e.time);
      event.set_kind(std::string(queue::to_string(e.kind)));
      event.set_type(e.type);
      event.set_src(e.src);
      event.set_dest(e.dest);
      if (e.link_figures) {
        EXPECT_TRUE(event.mutable_link()->ParseFromString(*e.link_figures));
      }
    }
    return out;
  }

  core::SimulatedScheduler scheduler{core::Clock::time_point(std::chrono::seconds(1'748'772'000))};
  std::shared_ptr<drivers::SimChannel> channel = drivers::SimChannel::create(/*seed=*/11);
  std::string env_file;
  std::unique_ptr<testing::SimNode> vehicle, buoy;
};

TEST(LinkCalibrationNetwork, PlantedExcessLossAndReceptionCurveAreCalibratedBackFromTheEventLog) {
  testing::TempDir dir("acomms-calibration");
  Network net(dir);
  net.run(400);

  const std::vector<v1::Event> events = net.buoy_events();
  std::size_t skipped = 0;
  const std::vector<eval::PacketSample> samples = eval::packet_samples(events, &skipped);
  // Every packet the buoy heard after its first grid is there, lost ones too.
  ASSERT_GE(samples.size(), 390u);
  EXPECT_EQ(skipped, 0u);
  const auto decoded = std::count_if(samples.begin(), samples.end(), [](const auto& s) { return s.decoded; });
  EXPECT_GT(decoded, 50);
  EXPECT_LT(decoded, static_cast<long>(samples.size()) - 50);

  const std::vector<eval::LinkCalibration> links = eval::calibrate_links(samples);
  ASSERT_EQ(links.size(), 1u);
  const eval::LinkCalibration& link = links[0];
  EXPECT_EQ(link.src, 1);
  ASSERT_TRUE(link.excess) << link.excess_refused;
  ASSERT_EQ(link.rates.count(0), 1u);
  const eval::RateCalibration& rate = link.rates.at(0);
  ASSERT_TRUE(rate.curve) << rate.curve_refused;
  const double snr50 = link.physics_snr50_db(*rate.curve);
  std::printf("planted: excess loss %.2f dB, 50%% point %.2f dB, slope %.3f /dB\n", kExcessLossDb, kSnr50Db,
              kSlopePerDb);
  std::printf("recovered from %zu packets (%ld decoded): excess loss %.2f dB (spread %.2f), 50%% point %.2f dB "
              "+/- %.2f, slope %.3f +/- %.3f /dB\n",
              samples.size(), static_cast<long>(decoded), link.excess->excess_loss_db(), link.excess->spread_db,
              snr50, rate.curve->snr50_ci95_db, rate.curve->slope_per_db, rate.curve->slope_ci95_per_db);
  EXPECT_NEAR(link.excess->excess_loss_db(), kExcessLossDb, 1.5);
  EXPECT_NEAR(snr50, kSnr50Db, 2.0);
  EXPECT_NEAR(rate.curve->slope_per_db, kSlopePerDb, 0.4);

  // The block goes into the simulator's config as is.
  v1::DriverConfig parsed;
  const std::string block = eval::physics_block(link);
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString("sim { " + block + " }", &parsed)) << block;
  const drivers::SimPhysicsConfig& physics = parsed.sim().physics();
  EXPECT_NEAR(physics.excess_loss_db(), kExcessLossDb, 1.5);
  ASSERT_EQ(physics.reception_size(), 1);
  EXPECT_EQ(physics.reception(0).rate(), 0);
  EXPECT_NEAR(physics.reception(0).snr50_db(), kSnr50Db, 2.0);
  EXPECT_NEAR(physics.reception(0).slope_per_db(), kSlopePerDb, 0.4);
}

TEST(LinkCalibrationNetwork, TooFewPacketsAreRefusedWithTheReason) {
  testing::TempDir dir("acomms-calibration-few");
  Network net(dir);
  net.run(8);

  const std::vector<eval::PacketSample> samples = eval::packet_samples(net.buoy_events());
  ASSERT_GE(samples.size(), 5u);  // heard and logged, just too few
  const std::vector<eval::LinkCalibration> links = eval::calibrate_links(samples);
  ASSERT_EQ(links.size(), 1u);
  EXPECT_FALSE(links[0].fitted());
  EXPECT_NE(links[0].excess_refused.find("too few decoded packets"), std::string::npos) << links[0].excess_refused;
  ASSERT_EQ(links[0].rates.count(0), 1u);
  EXPECT_NE(links[0].rates.at(0).curve_refused.find("too few packets to fit a reception curve"), std::string::npos)
      << links[0].rates.at(0).curve_refused;
  // The block says so rather than inventing figures.
  const std::string block = eval::physics_block(links[0]);
  EXPECT_EQ(block.find("excess_loss_db:"), std::string::npos) << block;
  EXPECT_EQ(block.find("reception {"), std::string::npos) << block;
}

}  // namespace
}  // namespace acomms
