// Environment validation names the field and the bound; the spline is
// not-a-knot; the beam count rule gives the counts the spec lists.
#include <gtest/gtest.h>

#include "gram/beam_fan.h"
#include "gram/bellhop_import.h"
#include "gram/cubic_spline.h"
#include "gram/environment_validation.h"

namespace acomms::gram {
namespace {

Environment conformance_env(const std::string& name) {
  return import_bellhop_env_file(std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/" + name)
      .environment;
}

std::string error_of(const Environment& env) { return validate_environment(env).value_or("(valid)"); }

TEST(GramEnvironment, ValidationNamesTheFieldAndTheBound) {
  const Environment base = conformance_env("pekeris_500hz.env");
  ASSERT_EQ(validate_environment(base), std::nullopt);

  Environment e = base;
  e.mutable_sound_speed(1)->set_depth_m(0);
  EXPECT_EQ(error_of(e), "sound_speed[1].depth_m = 0 must be greater than sound_speed[0].depth_m = 0 "
                         "(depths strictly increasing)");
  e = base;
  e.mutable_sound_speed(0)->set_speed_mps(-1);
  EXPECT_EQ(error_of(e), "sound_speed[0].speed_mps = -1 must be greater than 0");
  e = base;
  e.set_frequency_hz(0);
  EXPECT_EQ(error_of(e), "frequency_hz = 0 must be greater than 0");
  e = base;
  e.set_source_depth_m(150);
  EXPECT_EQ(error_of(e), "source_depth_m = 150 must be inside the water column (0, 100)");
  e = base;
  e.set_launch_angle_min_deg(-95);
  EXPECT_NE(error_of(e).find("-90 < launch_angle_min_deg (-95)"), std::string::npos);
  e = base;
  e.mutable_bottom()->mutable_half_space()->set_density_ratio(0);
  EXPECT_EQ(error_of(e), "bottom.half_space.density_ratio = 0 must be greater than 0");
  e = base;
  e.set_receiver_depth_m(3, 120);
  EXPECT_EQ(error_of(e), "receiver_depth_m[3] = 120 must be within the water column [0, 100]");
  e = base;
  e.add_bathymetry()->set_depth_m(150);
  EXPECT_EQ(error_of(e), "bathymetry[0].depth_m = 150 must not be below the last sound_speed depth 100");
  e = base;
  ValidationLimits small;
  small.max_receivers = 100;
  EXPECT_EQ(validate_environment(e, small).value_or(""),
            "receiver grid has 9825 points; the limit is 100");
}

TEST(GramEnvironment, AutomaticBeamCountFollowsTheSpecRule) {
  // Spec §4.7: these are the counts BELLHOP chooses for NBEAMS = 0.
  EXPECT_EQ(automatic_beam_count(conformance_env("lloyd_mirror.env")), 500u);
  EXPECT_EQ(automatic_beam_count(conformance_env("pekeris_500hz.env")), 3141u);
  EXPECT_EQ(automatic_beam_count(conformance_env("pekeris_2000hz.env")), 2000u);
  EXPECT_EQ(automatic_beam_count(conformance_env("free_space.env")), 2000u);
  EXPECT_EQ(automatic_beam_count(conformance_env("free_space_thorp.env")), 20000u);
}

TEST(GramEnvironment, AGivenBeamCountIsHonoured) {
  Environment env = conformance_env("bench_munk_field.env");
  EXPECT_EQ(beam_count(env), 1000u);
  env.set_beam_count(0);
  EXPECT_NE(beam_count(env), 1000u);
}

TEST(GramCubicSpline, NotAKnotHasAContinuousThirdDerivativeAtTheSecondAndPenultimateNodes) {
  const std::vector<double> x = {0, 1, 2.5, 3, 4.5, 6};
  const std::vector<double> y = {1, 3, 2, 5, 4, 4.5};
  const CubicSpline s(x, y);
  auto third = [&](std::size_t i) {  // d2f changes linearly: slope = 6 d
    return (s.evaluate(i, x[i] + 1e-3).d2f - s.evaluate(i, x[i]).d2f) / 1e-3;
  };
  EXPECT_NEAR(third(0), third(1), 1e-6);
  EXPECT_NEAR(third(3), third(4), 1e-6);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    EXPECT_NEAR(s.evaluate(i, x[i]).f, y[i], 1e-12);
    EXPECT_NEAR(s.evaluate(i, x[i + 1]).f, y[i + 1], 1e-12);
    if (i + 2 < x.size()) {
      EXPECT_NEAR(s.evaluate(i, x[i + 1]).df, s.evaluate(i + 1, x[i + 1]).df, 1e-9);
      EXPECT_NEAR(s.evaluate(i, x[i + 1]).d2f, s.evaluate(i + 1, x[i + 1]).d2f, 1e-9);
    }
  }
}

TEST(GramCubicSpline, ThreePointsGiveTheParabolaAndTwoTheLine) {
  const CubicSpline parabola({0, 1, 3}, {0, 1, 9});  // y = x²
  EXPECT_NEAR(parabola.evaluate(1, 2.0).f, 4.0, 1e-12);
  EXPECT_NEAR(parabola.evaluate(0, 0.5).d2f, 2.0, 1e-12);
  const CubicSpline line({0, 2}, {1, 5});
  EXPECT_NEAR(line.evaluate(0, 1.0).f, 3.0, 1e-12);
  EXPECT_NEAR(line.evaluate(0, 1.0).d2f, 0.0, 1e-12);
}

}  // namespace
}  // namespace acomms::gram
