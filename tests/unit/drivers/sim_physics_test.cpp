// The simulator with physics (sim.physics): packets decode with the
// probability their modelled SNR gives, the model runs off the core thread
// behind the TlGridSource seam, the link keeps running on the last grid
// while a new one is computed, and the node's position (its navigation)
// moves what gets through the way the model predicts.
// Environment: 100 m of water at 2 kHz with a thermocline between 10 and
// 30 m over sand (small, so that each model run takes milliseconds).
#include <gtest/gtest.h>
#include <unistd.h>

#include <asio/executor_work_guard.hpp>
#include <asio/io_context.hpp>
#include <asio/post.hpp>
#include <cmath>
#include <deque>
#include <fstream>
#include <limits>
#include <mutex>
#include <set>
#include <thread>

#include "gram/bellhop_import.h"
#include "gram/tl_lookup.h"
#include "sim/sim_driver.h"
#include "sim/sim_physics.h"
#include "sim/tl_grid_source.h"

namespace acomms::drivers {
namespace {

using core::Clock;
using std::chrono::seconds;
using v1::ModemTransmission;

constexpr const char* kEnv = R"('test: 100 m, thermocline 10-30 m, 2 kHz'
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

std::string env_file() {
  static const std::string path = [] {
    std::string p = ::testing::TempDir() + "sim_physics_" + std::to_string(getpid()) + ".env";
    std::ofstream(p) << kEnv;
    return p;
  }();
  return path;
}

constexpr double kMaxRange = 2000, kRangeStep = 20, kDepthStep = 5, kNoise = 60;

// What the model says, computed here independently of the driver: the TL
// grid with the receiving node as the source, on the configured grid.
gram::TransmissionLoss reference_grid(double source_depth_m) {
  gram::Environment env = gram::import_bellhop_env_file(env_file()).environment;
  env.clear_receiver_depth_m();
  env.clear_receiver_range_m();
  for (int i = 0; i <= 20; ++i) env.add_receiver_depth_m(i * kDepthStep);
  for (int i = 0; i <= 100; ++i) env.add_receiver_range_m(i * kRangeStep);
  env.set_source_depth_m(source_depth_m);
  return gram::compute_transmission_loss(env, {1});
}

// The GRAM pool, stood in: tasks wait until the test lets them run, then run
// on a thread of their own; answers come back through a queue the test's
// thread (the core thread here) drains.
class PoolStandIn {
 public:
  std::shared_ptr<TlGridSource> source() {
    return std::make_shared<ExecutorTlGridSource>(
        [this](std::function<void()> task) { waiting_.push_back(std::move(task)); },
        [this](std::function<void()> task) {
          std::lock_guard lock(mutex_);
          to_core_.push_back(std::move(task));
        });
  }
  std::size_t waiting() const { return waiting_.size(); }
  // Runs what waits on a worker thread, then hands the answers to the core.
  std::size_t release() {
    auto tasks = std::move(waiting_);
    waiting_.clear();
    std::thread worker([&] {
      worker_ids_.insert(std::this_thread::get_id());
      for (auto& task : tasks) task();
    });
    worker.join();
    std::deque<std::function<void()>> answers;
    {
      std::lock_guard lock(mutex_);
      answers.swap(to_core_);
    }
    for (auto& answer : answers) answer();
    return tasks.size();
  }
  // Releases until nothing is asked for any more (a grid, then spreads...).
  void settle() {
    while (release() > 0) {
    }
  }
  const std::set<std::thread::id>& worker_ids() const { return worker_ids_; }

 private:
  std::deque<std::function<void()>> waiting_;
  std::mutex mutex_;
  std::deque<std::function<void()>> to_core_;
  std::set<std::thread::id> worker_ids_;
};

// The vehicle's navigation, stood in (telemetry's SubmitNavigation later).
class Navigation final : public NodePositionSource {
 public:
  SimPosition position() const override { return at; }
  SimPosition at;
};

v1::DriverConfig physics_config(int id, double x, double depth) {
  v1::DriverConfig c;
  c.set_name("sim");
  c.set_modem_id(id);
  c.mutable_sim()->mutable_position()->set_x(x);
  c.mutable_sim()->mutable_position()->set_z(-depth);
  auto* p = c.mutable_sim()->mutable_physics();
  p->set_env_file(env_file());
  p->set_noise_level_db(kNoise);
  p->set_max_range_m(kMaxRange);
  p->set_range_step_m(kRangeStep);
  p->set_depth_step_m(kDepthStep);
  return c;
}

struct Node {
  Node(core::Scheduler& scheduler, std::shared_ptr<SimChannel> channel, const v1::DriverConfig& config,
       std::shared_ptr<TlGridSource> model)
      : driver(config, scheduler, std::move(channel)) {
    driver.set_tl_grid_source(std::move(model));
    link::DriverCallbacks callbacks;
    callbacks.on_receive = [this](const ModemTransmission& tx) { received.push_back(tx); };
    callbacks.on_data_request = [](ModemTransmission* tx) { tx->add_frame("x"); };
    callbacks.on_transmit_result = [](const ModemTransmission&, bool, const std::string&) {};
    driver.start(callbacks);
  }
  void send(int dest) {
    ModemTransmission tx;
    tx.set_src(driver.modem_id());
    tx.set_dest(dest);
    tx.set_rate(0);
    driver.initiate_transmission(tx);
  }
  SimDriver driver;
  std::vector<ModemTransmission> received;
};

class SimPhysicsTest : public ::testing::Test {
 protected:
  SimPhysicsTest() : scheduler_(Clock::time_point(seconds(1'700'000'000))) {}
  // One packet from `from` to `to`, the time for it to arrive, and the
  // model's answers released after it.
  void exchange(Node& from, Node& to) {
    from.send(to.driver.modem_id());
    scheduler_.run_for(seconds(10));
  }
  core::SimulatedScheduler scheduler_;
  std::shared_ptr<SimChannel> channel_ = SimChannel::create(7);
  PoolStandIn pool_;
};

TEST_F(SimPhysicsTest, ReportedSnrIsSourceLevelLessModelledLossLessNoise) {
  Node buoy(scheduler_, channel_, physics_config(1, 0, 30), pool_.source());
  Node vehicle(scheduler_, channel_, physics_config(2, 600, 50), pool_.source());
  pool_.settle();
  ASSERT_EQ(buoy.driver.physics()->grid_depth_m(), 30.0);
  // Lossless enough that it gets through: check the figures it carries.
  exchange(vehicle, buoy);
  ASSERT_EQ(buoy.received.size(), 1u);
  const auto& f = buoy.received[0].figures();
  const double tl = gram::tl_at(reference_grid(30), 600, 50);
  EXPECT_NEAR(f.snr_in_db(), 190 - tl - kNoise, 1e-9);
  EXPECT_DOUBLE_EQ(f.range_m(), 600);
  EXPECT_FALSE(f.has_delay_spread_s());  // asked for now, not known yet
  pool_.settle();
  exchange(vehicle, buoy);
  ASSERT_EQ(buoy.received.size(), 2u);
  ASSERT_TRUE(buoy.received[1].figures().has_delay_spread_s());
  EXPECT_GT(buoy.received[1].figures().delay_spread_s(), 0);
  EXPECT_LT(buoy.received[1].figures().delay_spread_s(), 0.1);
  EXPECT_NE(buoy.received[1].link_quality().find("snr_db="), std::string::npos);
}

// The site's corrections (gram/site_correction.h): the receiver's reported
// SNR is lower by the excess loss and by its own noise, powers summed.
TEST_F(SimPhysicsTest, ReportedSnrCarriesTheSitesExcessLossAndTheReceiversOwnNoise) {
  v1::DriverConfig buoy_config = physics_config(1, 0, 30);
  buoy_config.mutable_sim()->mutable_physics()->set_excess_loss_db(7.5);
  buoy_config.mutable_sim()->mutable_physics()->set_own_ship_noise_db(kNoise);
  Node buoy(scheduler_, channel_, buoy_config, pool_.source());
  Node vehicle(scheduler_, channel_, physics_config(2, 600, 50), pool_.source());
  pool_.settle();
  exchange(vehicle, buoy);
  ASSERT_EQ(buoy.received.size(), 1u);
  const double tl = gram::tl_at(reference_grid(30), 600, 50);
  EXPECT_NEAR(buoy.received[0].figures().snr_in_db(), 190 - tl - 7.5 - (kNoise + 10 * std::log10(2.0)), 1e-9);
}

TEST_F(SimPhysicsTest, TheModelNeverRunsOnTheCoreThreadAndTheLinkRunsOnTheOldGridMeanwhile) {
  Node buoy(scheduler_, channel_, physics_config(1, 0, 30), pool_.source());
  auto nav = std::make_shared<Navigation>();
  nav->at = {800, 0, -50};
  Node vehicle(scheduler_, channel_, physics_config(2, 0, 0), pool_.source());
  vehicle.driver.set_position_source(nav);
  pool_.settle();
  ASSERT_EQ(vehicle.driver.physics()->grid_depth_m(), 0 + 1.0)  // started at the config's surface (1 m inside)
      << "the grid follows the position only once the driver looks at it";
  exchange(vehicle, buoy);  // the vehicle sends from 50 m: it asks for a grid there
  pool_.settle();
  ASSERT_EQ(vehicle.driver.physics()->grid_depth_m(), 50.0);
  const std::uint64_t grids = vehicle.driver.physics()->grids_received();

  // The vehicle dives to 80 m; the pool is blocked: nothing it is asked runs.
  vehicle.received.clear();  // the buoy's ACK
  nav->at.z = -80;
  exchange(buoy, vehicle);
  ASSERT_GE(pool_.waiting(), 1u) << "a new grid was asked for";
  ASSERT_EQ(vehicle.received.size(), 1u) << "the link did not wait for the model";
  // Judged on the old grid (source at 50 m), at the buoy's 30 m.
  const double old_snr = 190 - gram::tl_at(reference_grid(50), 800, 30) - kNoise;
  EXPECT_NEAR(vehicle.received[0].figures().snr_in_db(), old_snr, 1e-9);
  exchange(buoy, vehicle);
  ASSERT_EQ(vehicle.received.size(), 2u);
  EXPECT_NEAR(vehicle.received[1].figures().snr_in_db(), old_snr, 1e-9);
  EXPECT_EQ(vehicle.driver.physics()->grids_received(), grids);

  pool_.settle();  // the new grid arrives
  EXPECT_EQ(vehicle.driver.physics()->grid_depth_m(), 80.0);
  exchange(buoy, vehicle);
  ASSERT_EQ(vehicle.received.size(), 3u);
  EXPECT_NEAR(vehicle.received[2].figures().snr_in_db(), 190 - gram::tl_at(reference_grid(80), 800, 30) - kNoise,
              1e-9);
  EXPECT_FALSE(pool_.worker_ids().count(std::this_thread::get_id()));
  EXPECT_FALSE(pool_.worker_ids().empty());
}

TEST_F(SimPhysicsTest, PacketsHeardBeforeTheFirstGridAreLostAndCounted) {
  Node buoy(scheduler_, channel_, physics_config(1, 0, 30), pool_.source());
  Node vehicle(scheduler_, channel_, physics_config(2, 300, 50), pool_.source());
  exchange(vehicle, buoy);
  EXPECT_TRUE(buoy.received.empty());
  EXPECT_EQ(buoy.driver.stats().lost_no_model, 1u);
  pool_.settle();
  exchange(vehicle, buoy);
  EXPECT_EQ(buoy.received.size(), 1u);
}

TEST_F(SimPhysicsTest, ChangingTheVehiclesDepthThroughItsNavigationChangesWhatGetsThroughAsTheModelPredicts) {
  // Two depths at 1500 m that the model ranks apart (a thermocline shadows
  // the warm layer from a source below it), and a noise level that puts
  // the decoding threshold between them.
  const gram::TransmissionLoss buoy_grid = reference_grid(30);
  const double range = 1500;
  double worst = 5, best = 5;
  for (double z = 5; z <= 90; z += 5) {
    if (gram::tl_at(buoy_grid, range, z) > gram::tl_at(buoy_grid, range, worst)) worst = z;
    if (gram::tl_at(buoy_grid, range, z) < gram::tl_at(buoy_grid, range, best)) best = z;
  }
  const double tl_worst = gram::tl_at(buoy_grid, range, worst), tl_best = gram::tl_at(buoy_grid, range, best);
  ASSERT_GT(tl_worst - tl_best, 2.0) << "worst " << worst << " m, best " << best << " m";
  const double noise = 190 - (tl_worst + tl_best) / 2 - 10;  // the FSK midpoint halfway between
  v1::DriverConfig buoy_config = physics_config(1, 0, 30), vehicle_config = physics_config(2, 0, 0);
  buoy_config.mutable_sim()->mutable_physics()->set_noise_level_db(noise);
  vehicle_config.mutable_sim()->mutable_physics()->set_noise_level_db(noise);
  Node buoy(scheduler_, channel_, buoy_config, pool_.source());
  auto nav = std::make_shared<Navigation>();
  Node vehicle(scheduler_, channel_, vehicle_config, pool_.source());
  vehicle.driver.set_position_source(nav);
  pool_.settle();
  const gram::LinkPhysics& physics = buoy.driver.physics()->link_physics();
  auto p_at = [&](double tl) { return gram::link_outcome(physics, tl, 0).probability; };

  auto count_at = [&](double depth) {
    nav->at = {range, 0, -depth};
    buoy.received.clear();
    for (int i = 0; i < 200; ++i) {
      exchange(vehicle, buoy);
      pool_.settle();
    }
    return buoy.received.size();
  };
  const std::size_t at_worst = count_at(worst), at_best = count_at(best);
  EXPECT_LT(at_worst, at_best);
  const double pw = p_at(tl_worst), pb = p_at(tl_best);
  EXPECT_NEAR(at_worst / 200.0, pw, 5 * std::sqrt(pw * (1 - pw) / 200) + 0.01);
  EXPECT_NEAR(at_best / 200.0, pb, 5 * std::sqrt(pb * (1 - pb) / 200) + 0.01);
}

TEST_F(SimPhysicsTest, WithoutAModelWorkerOnASharedChannelTheDriverRefusesToStart) {
  SimDriver driver(physics_config(1, 0, 30), scheduler_, channel_);
  link::DriverCallbacks callbacks;
  EXPECT_THROW(driver.start(callbacks), link::DriverError);
}

TEST_F(SimPhysicsTest, ConfigErrorsNameTheField) {
  auto expect_error = [&](v1::DriverConfig c, const std::string& field) {
    try {
      SimDriver driver(c, scheduler_, channel_);
      ADD_FAILURE() << "accepted: " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  v1::DriverConfig c = physics_config(1, 0, 30);
  c.mutable_sim()->mutable_physics()->clear_env_file();
  expect_error(c, "driver.sim.physics.env_file is required");
  c = physics_config(1, 0, 30);
  c.mutable_sim()->mutable_physics()->set_env_file("/nonexistent.env");
  expect_error(c, "driver.sim.physics.env_file");
  c = physics_config(1, 0, 30);
  c.mutable_sim()->mutable_physics()->mutable_noise_model()->set_sea_state(9);
  expect_error(c, "driver.sim.physics.noise_model.sea_state must be in 0..6");
  c = physics_config(1, 0, 30);
  c.mutable_sim()->mutable_physics()->add_reception()->set_rate(7);
  expect_error(c, "driver.sim.physics.reception[0].rate must be in 0..5");
  c = physics_config(1, 0, 30);
  c.mutable_sim()->mutable_physics()->set_range_step_m(-1);
  expect_error(c, "driver.sim.physics.range_step_m");
  c = physics_config(1, 0, 30);
  c.mutable_sim()->mutable_physics()->set_excess_loss_db(std::numeric_limits<double>::infinity());
  expect_error(c, "driver.sim.physics.excess_loss_db");
  c = physics_config(1, 0, 30);
  c.mutable_sim()->mutable_physics()->set_own_ship_noise_db(std::nan(""));
  expect_error(c, "driver.sim.physics.own_ship_noise_db");
}

TEST(TlGridSourceTest, TheDaemonsOwnWorkerComputesOffTheLoopAndAnswersOnIt) {
  asio::io_context io;
  auto worker = std::make_shared<WorkerThread>();
  ExecutorTlGridSource source([worker](std::function<void()> task) { worker->post(std::move(task)); },
                              [&io](std::function<void()> task) { asio::post(io, std::move(task)); });
  ModelRun run;
  run.environment = gram::import_bellhop_env_file(env_file()).environment;
  std::thread::id answered_on;
  std::shared_ptr<const gram::TransmissionLoss> tl;
  source.request(run, [&](ModelAnswer answer) {
    answered_on = std::this_thread::get_id();
    tl = answer.tl;
  });
  auto guard = asio::make_work_guard(io);
  while (!tl && io.run_one_for(std::chrono::seconds(30)) > 0) {
  }
  ASSERT_TRUE(tl);
  EXPECT_EQ(answered_on, std::this_thread::get_id());
  EXPECT_EQ(tl->tl_db.size(), 1u);
}

}  // namespace
}  // namespace acomms::drivers
