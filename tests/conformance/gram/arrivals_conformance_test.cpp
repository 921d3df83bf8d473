// Arrivals and RMS delay spread of the lossy Pekeris case against the
// image-method eigenrays (README §3 bands): delay 2 µs, amplitude 3 %,
// angles 0.01°, bounce counts exact for arrivals above −40 dB; τ_rms 2 %.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "csv_table.h"
#include "gram/arrivals.h"
#include "gram/beam_fan.h"
#include "gram/bellhop_import.h"

namespace acomms::gram {
namespace {

using test::CsvTable;

class GramArrivals : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    Environment env =
        import_bellhop_env_file(test::conformance_path("envs/pekeris_lossy_500hz.env")).environment;
    const CsvTable spread("delay_spread_pekeris_lossy.csv");
    // The file's own automatic count (its grid reaches 10 km); with only
    // these receivers the rule would choose fewer beams.
    env.set_beam_count(automatic_beam_count(env));
    env.clear_receiver_range_m();
    env.clear_receiver_depth_m();
    env.set_irregular_receivers(true);
    for (std::size_t i = 0; i < spread.size(); ++i) {
      env.add_receiver_range_m(spread.at(i, "range_m"));
      env.add_receiver_depth_m(spread.at(i, "depth_m"));
    }
    results_ = new std::vector<ReceiverArrivals>(compute_arrivals(env));
  }
  static void TearDownTestSuite() { delete results_; }

  static const ReceiverArrivals& at(double range, double depth) {
    for (const auto& r : *results_)
      if (r.range_m == range && r.depth_m == depth) return r;
    throw std::runtime_error("no receiver");
  }
  static std::vector<ReceiverArrivals>* results_;
};
std::vector<ReceiverArrivals>* GramArrivals::results_ = nullptr;

double angle_difference_deg(double a, double b) {
  return std::abs(std::remainder(a - b, 360.0));
}

TEST_F(GramArrivals, EveryPathAboveMinus40dBMatchesTheImageMethod) {
  const CsvTable table("arrivals_pekeris_lossy.csv");
  std::size_t checked = 0;
  std::vector<double> amplitude_errors;
  for (std::size_t row = 0; row < table.size(); ++row) {
    const double range = table.at(row, "range_m"), depth = table.at(row, "depth_m");
    double strongest = 0;
    for (std::size_t k = 0; k < table.size(); ++k)
      if (table.at(k, "range_m") == range && table.at(k, "depth_m") == depth)
        strongest = std::max(strongest, table.at(k, "amp_abs"));
    const double amp = table.at(row, "amp_abs");
    if (20 * std::log10(amp / strongest) < -40) continue;
    const int top = static_cast<int>(table.at(row, "n_surface"));
    const int bottom = static_cast<int>(table.at(row, "n_bottom"));
    const double delay = table.at(row, "delay_s");
    const Arrival* match = nullptr;
    for (const auto& a : at(range, depth).arrivals)
      if (a.top_bounces == top && a.bottom_bounces == bottom &&
          (!match || std::abs(a.delay_s - delay) < std::abs(match->delay_s - delay)))
        match = &a;
    SCOPED_TRACE("receiver (" + std::to_string(range) + ", " + std::to_string(depth) + ") row " +
                 std::to_string(row));
    ASSERT_NE(match, nullptr) << "no arrival with " << top << " surface and " << bottom << " bottom bounces";
    EXPECT_NEAR(match->delay_s, delay, 2e-6);
    EXPECT_NEAR(match->amplitude, amp, 0.03 * amp);
    EXPECT_NEAR(match->launch_deg, table.at(row, "launch_deg"), 0.01);
    EXPECT_NEAR(match->arrival_deg, table.at(row, "arrival_deg"), 0.01);
    EXPECT_LE(angle_difference_deg(match->phase_deg, table.at(row, "amp_phase_deg")), 2.0);
    amplitude_errors.push_back(std::abs(match->amplitude / amp - 1));
    ++checked;
  }
  std::sort(amplitude_errors.begin(), amplitude_errors.end());
  std::cout << checked << " arrivals checked; amplitude error median "
            << 100 * amplitude_errors[amplitude_errors.size() / 2] << " %, max "
            << 100 * amplitude_errors.back() << " %\n";
  EXPECT_GE(checked, 30u);
}

TEST_F(GramArrivals, RmsDelaySpreadWithinTwoPercent) {
  const CsvTable table("delay_spread_pekeris_lossy.csv");
  for (std::size_t row = 0; row < table.size(); ++row) {
    const auto& r = at(table.at(row, "range_m"), table.at(row, "depth_m"));
    const DelaySpread spread = rms_delay_spread(r.arrivals, 60.0);
    const double want = table.at(row, "tau_rms_s");
    std::cout << "(" << r.range_m << ", " << r.depth_m << "): tau_rms " << spread.tau_rms_s
              << " s (reference " << want << "), " << spread.arrivals_used << " arrivals\n";
    EXPECT_NEAR(spread.tau_rms_s, want, 0.02 * want);
    EXPECT_NEAR(spread.first_delay_s, table.at(row, "first_delay_s"), 2e-6);
  }
}

TEST(GramDelaySpread, IsZeroForOneArrivalAndHalfTheGapForTwoEqualOnes) {
  EXPECT_EQ(rms_delay_spread({Arrival{.delay_s = 1.0, .amplitude = 1.0}}).tau_rms_s, 0.0);
  const auto two = rms_delay_spread({Arrival{.delay_s = 1.0, .amplitude = 0.5},
                                     Arrival{.delay_s = 1.2, .amplitude = 0.5}});
  EXPECT_NEAR(two.tau_rms_s, 0.1, 1e-12);
  // Below the floor: ignored.
  const auto floor = rms_delay_spread({Arrival{.delay_s = 1.0, .amplitude = 1.0},
                                       Arrival{.delay_s = 9.0, .amplitude = 1e-4}}, 60.0);
  EXPECT_EQ(floor.arrivals_used, 1u);
}

}  // namespace
}  // namespace acomms::gram
