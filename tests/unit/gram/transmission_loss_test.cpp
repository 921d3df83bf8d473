// Properties of a model run: thread-count independence, the flat .bty,
// the source axis and shadows.
#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "gram/bellhop_import.h"
#include "gram/transmission_loss.h"

namespace acomms::gram {
namespace {

Environment conformance_env(const std::string& name) {
  return import_bellhop_env_file(std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/" + name)
      .environment;
}

// A smaller Pekeris run to keep the tests quick.
Environment small_pekeris() {
  Environment env = conformance_env("pekeris_lossy_500hz.env");
  env.clear_receiver_range_m();
  for (int i = 0; i <= 40; ++i) env.add_receiver_range_m(100.0 * i);
  env.set_beam_count(800);
  env.set_box_range_m(4100);
  return env;
}

TEST(GramTransmissionLoss, IsBitIdenticalWhateverTheThreadCount) {
  for (FieldMode mode : {COHERENT, INCOHERENT}) {
    Environment env = small_pekeris();
    env.set_field_mode(mode);
    const auto one = compute_transmission_loss(env, {1});
    const auto two = compute_transmission_loss(env, {2});
    const auto five = compute_transmission_loss(env, {5});
    ASSERT_EQ(one.tl_db.size(), two.tl_db.size());
    EXPECT_EQ(std::memcmp(one.tl_db.data(), two.tl_db.data(), one.tl_db.size() * sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(one.tl_db.data(), five.tl_db.data(), one.tl_db.size() * sizeof(double)), 0);
  }
}

// A grid of 40,200 receivers: the chunks' sums and the TL are computed on
// several threads too, in slices of the receivers; the slices must meet.
TEST(GramTransmissionLoss, ALargeGridIsBitIdenticalWhateverTheThreadCount) {
  Environment env = conformance_env("lloyd_mirror.env");
  env.clear_receiver_range_m();
  for (int i = 1; i <= 200; ++i) env.add_receiver_range_m(25.0 * i);
  env.clear_receiver_depth_m();
  for (int i = 0; i <= 200; ++i) env.add_receiver_depth_m(i);
  env.set_box_range_m(5100);
  env.set_beam_count(2000);  // enough ray steps for the run to take several threads
  for (FieldMode mode : {COHERENT, INCOHERENT}) {
    env.set_field_mode(mode);
    RunOptions options;
    options.keep_pressure = true;
    options.threads = 1;
    const auto one = compute_transmission_loss(env, options);
    ASSERT_EQ(one.tl_db.size(), 40200u);
    EXPECT_EQ(std::count_if(one.tl_db.begin(), one.tl_db.end(), [](double tl) { return std::isfinite(tl); }), 40200);
    for (unsigned threads : {2u, 3u}) {
      options.threads = threads;
      const auto many = compute_transmission_loss(env, options);
      ASSERT_EQ(many.tl_db.size(), one.tl_db.size());
      EXPECT_EQ(std::memcmp(one.tl_db.data(), many.tl_db.data(), one.tl_db.size() * sizeof(double)), 0)
          << threads << " threads";
      ASSERT_EQ(many.pressure.size(), one.pressure.size());
      EXPECT_EQ(std::memcmp(one.pressure.data(), many.pressure.data(), one.pressure.size() * sizeof(one.pressure[0])), 0)
          << threads << " threads";
    }
  }
}

TEST(GramTransmissionLoss, AFlatBathymetryGivesTheFlatBottomResult) {
  const Environment flat = small_pekeris();
  Environment with_bty = flat;
  for (double r : {0.0, 1500.0, 6000.0}) {
    auto* p = with_bty.add_bathymetry();
    p->set_range_m(r);
    p->set_depth_m(100);
  }
  const auto a = compute_transmission_loss(flat);
  const auto b = compute_transmission_loss(with_bty);
  ASSERT_EQ(a.tl_db.size(), b.tl_db.size());
  for (std::size_t i = 0; i < a.tl_db.size(); ++i) {
    if (std::isnan(a.tl_db[i])) {
      EXPECT_TRUE(std::isnan(b.tl_db[i]));
      continue;
    }
    EXPECT_NEAR(a.tl_db[i], b.tl_db[i], 0.01) << "receiver " << i;
  }
}

TEST(GramTransmissionLoss, ARangeDependentBottomWithASeamountGivesFiniteLossInTheWater) {
  // Up a slope to 50 m at 4 km, down again: rays steepen, turn back in range
  // and cross segment ends in both directions; every run must end.
  Environment env = small_pekeris();
  env.clear_sound_speed();
  for (auto [z, c] : {std::pair{0.0, 1520.0}, {30.0, 1510.0}, {60.0, 1495.0}, {200.0, 1500.0}}) {
    auto* p = env.add_sound_speed();
    p->set_depth_m(z);
    p->set_speed_mps(c);
  }
  for (auto [r, z] : {std::pair{0.0, 200.0}, {2000.0, 120.0}, {3000.0, 50.0}, {3500.0, 180.0}}) {
    auto* p = env.add_bathymetry();
    p->set_range_m(r);
    p->set_depth_m(z);
  }
  env.set_box_depth_m(201);
  env.set_beam_count(400);
  for (FieldMode mode : {COHERENT, INCOHERENT}) {
    env.set_field_mode(mode);
    const auto tl = compute_transmission_loss(env);
    const std::size_t nr = tl.range_m.size();
    for (std::size_t iz = 0; iz < tl.depth_m.size(); ++iz)
      for (std::size_t ir = 1; ir < nr; ++ir) {
        const double v = tl.tl_db[iz * nr + ir];
        EXPECT_FALSE(std::isnan(v));
        // In the water up to the slope (bottom ≥ 120 m until 2 km), the field is there.
        if (tl.range_m[ir] <= 2000 && tl.depth_m[iz] < 100) {
          EXPECT_TRUE(std::isfinite(v)) << iz << "," << ir;
        }
      }
  }
}

TEST(GramTransmissionLoss, TheSourceAxisHasNoValueAndDoesNotCrash) {
  const auto tl = compute_transmission_loss(small_pekeris());
  const std::size_t nr = tl.range_m.size();
  for (std::size_t iz = 0; iz < tl.depth_m.size(); ++iz) {
    EXPECT_TRUE(std::isnan(tl.tl_db[iz * nr]));
    EXPECT_TRUE(std::isfinite(tl.tl_db[iz * nr + 1]));
  }
}

TEST(GramTransmissionLoss, ReceiversOutsideTheFanAreInShadow) {
  Environment env = conformance_env("free_space.env");
  env.set_launch_angle_min_deg(-10);
  env.set_launch_angle_max_deg(10);
  env.set_beam_count(200);
  const auto tl = compute_transmission_loss(env);
  const std::size_t nr = tl.range_m.size();
  // 500 m above the source at 100 m range is 79° up: no beam goes there.
  EXPECT_TRUE(std::isinf(tl.tl_db[0 * nr + 0]));
}

TEST(GramTransmissionLoss, AnInvalidEnvironmentIsRefusedWithTheValidationMessage) {
  Environment env = small_pekeris();
  env.set_frequency_hz(-5);
  try {
    compute_transmission_loss(env);
    FAIL() << "ran";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "frequency_hz = -5 must be greater than 0");
  }
}

}  // namespace
}  // namespace acomms::gram
