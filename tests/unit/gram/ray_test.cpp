// Ray tracing against closed forms: in a constant gradient c = c0 + g z a
// ray is a circular arc; it turns where c = c(z_s)/cos θ0, even when a
// c-linear node lies between the turning depth and the ray's step.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "gram/medium.h"
#include "gram/ray.h"

namespace acomms::gram {
namespace {

constexpr double kGradient = 0.05;  // 1/s

Environment gradient_environment() {
  Environment env;
  env.set_frequency_hz(100);
  for (int i = 0; i <= 10; ++i) {  // nodes every 100 m, all on one line
    auto* p = env.add_sound_speed();
    p->set_depth_m(100.0 * i);
    p->set_speed_mps(1500 + kGradient * 100.0 * i);
  }
  env.set_source_depth_m(50);
  env.set_step_m(5);
  env.set_box_depth_m(1001);
  env.set_box_range_m(20000);
  env.mutable_surface()->set_kind(Boundary::VACUUM);
  env.mutable_bottom()->set_kind(Boundary::RIGID);
  return env;
}

TEST(GramRay, TurnsAtTheDepthWhereSnellsLawSaysAndNotOnTheNextNode) {
  const Environment env = gradient_environment();
  const Medium medium(env);
  const double angle = 5.0 * std::numbers::pi / 180.0;
  const double c_source = 1500 + kGradient * 50;
  const double c_turn = c_source / std::cos(angle);
  const double z_turn = (c_turn - 1500) / kGradient;         // 164.8 m: between nodes 100 and 200
  const double r_turn = c_turn / kGradient * std::sin(angle);  // circle radius × sin θ0
  RayTracer ray(medium, angle);
  double z_max = 0, r_at_max = 0, r_back = 0;
  while (ray.next()) {
    const RayPoint& p = ray.point();
    if (p.z > z_max) { z_max = p.z; r_at_max = p.r; }
    if (r_back == 0 && p.r > r_turn && p.z <= 50) r_back = p.r;
  }
  EXPECT_NEAR(z_max, z_turn, 0.01);
  EXPECT_NEAR(r_at_max, r_turn, 5.0);  // the step (5 m) resolves the turning range
  EXPECT_NEAR(r_back, 2 * r_turn, 5.0);
}

TEST(GramRay, TravelTimeToTheTurningPointFollowsTheCircularArc) {
  const Environment env = gradient_environment();
  const Medium medium(env);
  RayTracer ray(medium, 10.0 * std::numbers::pi / 180.0);
  // On the exact arc from θ0 down to the turning point (θ = 0):
  // τ = (1/g) ln((1 + sin θ0) / cos θ0).
  const double theta0 = 10.0 * std::numbers::pi / 180.0;
  const double tau_turn = (1.0 / kGradient) * std::log((1 + std::sin(theta0)) / std::cos(theta0));
  double best_z = 0, tau_at_best = 0;
  while (ray.next())
    if (ray.point().z > best_z) { best_z = ray.point().z; tau_at_best = ray.point().tau; }
  EXPECT_NEAR(tau_at_best, tau_turn, 2e-4);
}

TEST(GramRay, ReflectsOffTheSurfaceWithAPhaseOfPi) {
  const Environment env = gradient_environment();
  const Medium medium(env);
  RayTracer ray(medium, -20.0 * std::numbers::pi / 180.0);
  while (ray.next() && ray.point().top_bounces == 0) {}
  EXPECT_EQ(ray.point().top_bounces, 1);
  EXPECT_DOUBLE_EQ(ray.point().z, 0.0);
  EXPECT_DOUBLE_EQ(ray.point().reflection.real(), -1.0);
  EXPECT_GT(ray.point().zeta, 0.0);  // heading down again
}

}  // namespace
}  // namespace acomms::gram
