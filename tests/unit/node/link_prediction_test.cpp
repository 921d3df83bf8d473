// The model's prediction for packets a real modem hears
// (node/link_prediction.h), on GRAM's real pool and built-in model in free
// field (the surface and bottom are water: nothing reflects, so TL is
// spherical spreading, 20 log10 r): which positions it takes, that it waits
// for the grid rather than guessing, and its refusals.
#include "node/link_prediction.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <mutex>
#include <thread>

#include "gram/model_engine.h"
#include "gram/model_pool.h"
#include "gram/vehicle_environment.h"
#include "free_field_environment.h"

namespace acomms::node {
namespace {

// Free field (free_field_environment.h): TL is 20 log10(r).
constexpr const char* kFreeField = acomms::test::kFreeFieldEnvironment;

class LinkPredictionTest : public ::testing::Test {
 protected:
  LinkPredictionTest() {
    gram::Environment base;
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(kFreeField, &base));
    environment_ = std::make_unique<gram::VehicleEnvironment>(base, gram::VehicleEnvironmentOptions{});
    pool_ = std::make_unique<gram::ModelPool>(gram::ModelPoolOptions{1, 16, 1 << 20}, gram::make_builtin_engine());
  }

  std::shared_ptr<LinkPrediction> make(const std::string& text) {
    drivers::MicroModemPrediction config;
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &config)) << text;
    PredictionSources sources{1, &own_, &others_, environment_.get(), pool_.get(),
                              [this](std::function<void()> task) {
                                std::lock_guard lock(mutex_);
                                tasks_.push_back(std::move(task));
                              },
                              [this] { return now_s_; }};
    return LinkPrediction::create(config, sources);
  }
  // Runs what was posted to the "core" (this thread) until `done`, 60 s at most.
  template <typename F>
  bool run_until(F done) {
    for (int i = 0; i < 6000 && !done(); ++i) {
      std::deque<std::function<void()>> now;
      {
        std::lock_guard lock(mutex_);
        now.swap(tasks_);
      }
      for (auto& task : now) task();
      if (now.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return done();
  }
  v1::LinkFigures predict(LinkPrediction& p, int32_t src = 2) {
    v1::ModemTransmission heard;
    heard.set_src(src);
    v1::LinkFigures figures;
    p.predict(heard, figures);
    return figures;
  }

  double now_s_ = 1'700'000'000;
  core::NodePosition own_;
  ModemPositions others_;
  std::unique_ptr<gram::VehicleEnvironment> environment_;
  std::unique_ptr<gram::ModelPool> pool_;
  std::mutex mutex_;
  std::deque<std::function<void()>> tasks_;
};

constexpr const char* kFixed =
    "source_level_db: 190 noise_level_db: 85 max_range_m: 1000 range_step_m: 10 "
    "fixed { modem: 1 position { x: 300 y: 0 z: -10 } } fixed { modem: 2 position { x: 0 y: 0 z: -10 } }";

TEST_F(LinkPredictionTest, WaitsForTheGridThenPredictsTheSonarEquation) {
  auto p = make(kFixed);
  EXPECT_FALSE(predict(*p).has_predicted_snr_db()) << "no grid yet: no guess";
  EXPECT_EQ(p->counters().no_model, 1u);
  ASSERT_TRUE(run_until([&] { return p->counters().grids == 1; }));
  const v1::LinkFigures f = predict(*p);
  ASSERT_TRUE(f.has_predicted_snr_db());
  EXPECT_NEAR(f.predicted_tl_db(), 20 * std::log10(300.0), 1.0);
  EXPECT_DOUBLE_EQ(f.predicted_snr_db(), 190 - f.predicted_tl_db() - 85);
  EXPECT_EQ(p->counters().predicted, 1u);
  // A farther sender: more loss, by about 20 log10(3).
  others_.set(2, core::NodeFix{now_s_ - 10, -600, 0, -10});
  const v1::LinkFigures far = predict(*p);
  ASSERT_TRUE(far.has_predicted_tl_db());
  EXPECT_NEAR(far.predicted_tl_db() - f.predicted_tl_db(), 20 * std::log10(3.0), 1.0);
  EXPECT_EQ(p->counters().grids, 1u) << "this node did not move: the same grid";
}

TEST_F(LinkPredictionTest, LivePositionsOverTheConfigsAndStaleOnesNotUsed) {
  auto p = make(kFixed);
  predict(*p);
  ASSERT_TRUE(run_until([&] { return p->counters().grids == 1; }));
  // The sender's telemetry puts it 500 m away; this node's navigation at
  // the same depth (so the grid holds).
  others_.set(2, core::NodeFix{now_s_ - 5, 800, 0, -10});
  own_.set(core::NodeFix{now_s_ - 1, 300, 0, -10});
  const v1::LinkFigures live = predict(*p);
  ASSERT_TRUE(live.has_predicted_tl_db());
  EXPECT_NEAR(live.predicted_tl_db(), 20 * std::log10(500.0), 1.0);
  // Fifteen minutes later the telemetry is stale: the config's place again.
  now_s_ += 900;
  const v1::LinkFigures stale = predict(*p);
  ASSERT_TRUE(stale.has_predicted_tl_db());
  EXPECT_NEAR(stale.predicted_tl_db(), 20 * std::log10(300.0), 1.0);
  // A sender with no position at all, and one beyond the grid.
  EXPECT_FALSE(predict(*p, 7).has_predicted_snr_db());
  EXPECT_EQ(p->counters().no_position, 1u);
  others_.set(2, core::NodeFix{now_s_, 5000, 0, -10});
  EXPECT_FALSE(predict(*p).has_predicted_snr_db());
  EXPECT_EQ(p->counters().out_of_range, 1u);
}

TEST_F(LinkPredictionTest, WithoutAnEnvironmentNothingIsPredicted) {
  environment_ = std::make_unique<gram::VehicleEnvironment>(gram::Environment(), gram::VehicleEnvironmentOptions{});
  auto p = make(kFixed);
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(predict(*p).has_predicted_snr_db());
  EXPECT_EQ(p->counters().no_model, 3u);
  std::lock_guard lock(mutex_);
  EXPECT_TRUE(tasks_.empty()) << "no model run was asked for";
  EXPECT_EQ(p->counters().grids, 0u);
}

// The hot path: predict runs for every packet heard, on the core thread.
// GRAM's environment is resolved (and serialized, the grid's key) once per
// VehicleEnvironment version, not per packet, and the predictions are the
// same with the cached water as with a fresh one: a version that moved
// without changing the water resolves it again, keeps the grid and gives
// the same figures to the last bit; many packets ask for no new model run.
TEST_F(LinkPredictionTest, TheEnvironmentIsResolvedOncePerVersionAndThePredictionsAreUnchanged) {
  auto p = make(kFixed);
  predict(*p);
  ASSERT_TRUE(run_until([&] { return p->counters().grids == 1; }));
  const v1::LinkFigures first = predict(*p);
  ASSERT_TRUE(first.has_predicted_snr_db());
  for (int i = 0; i < 100; ++i) {
    const v1::LinkFigures again = predict(*p);
    ASSERT_EQ(again.predicted_tl_db(), first.predicted_tl_db());
    ASSERT_EQ(again.predicted_snr_db(), first.predicted_snr_db());
  }
  EXPECT_EQ(p->counters().water_resolved, 1u) << "one resolve for 102 packets of one environment version";
  EXPECT_EQ(p->counters().grid_requests, 1u) << "the grid holds: no model run asked for again";
  // A new version with the same water (an empty change): resolved again,
  // the same grid kept, the same prediction.
  environment_->update(gram::EnvironmentChange{}, nullptr);
  const v1::LinkFigures after = predict(*p);
  EXPECT_EQ(p->counters().water_resolved, 2u);
  EXPECT_EQ(after.predicted_tl_db(), first.predicted_tl_db());
  EXPECT_EQ(after.predicted_snr_db(), first.predicted_snr_db());
  EXPECT_EQ(p->counters().grid_requests, 1u) << "the same water: the grid holds, no model run";
  // Other water (a deeper bottom): a new grid, for the new version only.
  gram::EnvironmentChange deeper;
  deeper.base = environment_->snapshot().base();
  deeper.base.mutable_sound_speed(1)->set_depth_m(200);
  environment_->update(deeper, nullptr);
  predict(*p);
  ASSERT_TRUE(run_until([&] { return p->counters().grids == 2; }));
  EXPECT_EQ(p->counters().water_resolved, 3u);
  EXPECT_EQ(p->counters().grid_requests, 2u);
  const v1::LinkFigures deep = predict(*p);
  ASSERT_TRUE(deep.has_predicted_tl_db());
  EXPECT_NEAR(deep.predicted_tl_db(), 20 * std::log10(300.0), 1.0);
}

TEST_F(LinkPredictionTest, BadSettingsAreRefusedNamingTheField) {
  try {
    make("source_level_db: 400");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("driver.micromodem.prediction.source_level_db"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make("range_step_m: -1"), std::invalid_argument);
  EXPECT_THROW(make("max_range_m: 100000 range_step_m: 1"), std::invalid_argument);
  EXPECT_THROW(make("noise_model { sea_state: 9 }"), std::invalid_argument);
  EXPECT_THROW(make("fixed { modem: 1 position { x: inf } }"), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::node
