// The ray/beam model against the exact and image-sum fields of
// shared/conformance/gram, at the README's suggested bands and with the
// environments' own (automatic) beam counts unless a test says otherwise.
// Every test prints its |ΔTL| statistics.
#include <iostream>

#include <gtest/gtest.h>

#include "csv_table.h"
#include "gram/bellhop_import.h"
#include "tl_comparison.h"

namespace acomms::gram {
namespace {

using test::compare;
using test::Comparison;
using test::CsvTable;

Environment load(const std::string& env_file) {
  return import_bellhop_env_file(test::conformance_path("envs/" + env_file)).environment;
}

Comparison run(const Environment& env, const std::string& csv, const std::string& column) {
  const TransmissionLoss tl = compute_transmission_loss(env);
  const Comparison c = compare(tl, CsvTable(csv), column);
  std::cout << env.title() << " [" << tl.beam_count << " beams] vs " << column
            << "\n  pointwise: " << c.pointwise << "\n  400-m averaged: " << c.averaged << "\n";
  return c;
}

TEST(GramField, FreeSpaceIsWithinFiveHundredthsOfADecibelEverywhere) {
  for (const char* name : {"free_space", "free_space_thorp", "free_space_fg"}) {
    const Comparison c = run(load(std::string(name) + ".env"), std::string(name) + ".csv", "tl_db");
    EXPECT_LE(c.pointwise.max, 0.05) << name;
  }
}

TEST(GramField, LloydMirrorCoherentMedianAndNinetyFivePercentWithinOneDecibel) {
  const Comparison c = run(load("lloyd_mirror.env"), "lloyd_mirror.csv", "tl_coherent_db");
  EXPECT_LE(c.pointwise.median, 0.05);
  EXPECT_GE(c.pointwise.within_1db, 0.95);
}

TEST(GramField, LloydMirrorIncoherentMedianWithinOneHundredth) {
  const Comparison c = run(load("lloyd_mirror_inc.env"), "lloyd_mirror.csv", "tl_incoherent_db");
  EXPECT_LE(c.pointwise.median, 0.01);
}

TEST(GramField, LloydMirrorSemiCoherentWithTwoThousandBeams) {
  Environment env = load("lloyd_mirror_semi.env");
  env.set_beam_count(2000);
  const Comparison c = run(env, "lloyd_mirror.csv", "tl_semicoherent_db");
  EXPECT_LE(c.pointwise.median, 0.05);
}

TEST(GramField, LloydMirrorCoherentWithTwoThousandBeamsHasNinetyNinePercentWithinOneDecibel) {
  Environment env = load("lloyd_mirror.env");
  env.set_beam_count(2000);
  const Comparison c = run(env, "lloyd_mirror.csv", "tl_coherent_db");
  EXPECT_GE(c.pointwise.within_1db, 0.99);
}

void expect_pekeris(const std::string& name) {
  const Environment env = load(name + ".env");
  const TransmissionLoss tl = compute_transmission_loss(env);
  const CsvTable table(name + ".csv");
  const Comparison images = compare(tl, table, "tl_images_coherent_db");
  const Comparison exact = compare(tl, table, "tl_exact_db");
  std::cout << name << " [" << tl.beam_count << " beams]\n  vs images pointwise: " << images.pointwise
            << "\n  vs images 400-m averaged: " << images.averaged
            << "\n  vs exact pointwise: " << exact.pointwise
            << "\n  vs exact 400-m averaged: " << exact.averaged << "\n";
  EXPECT_LE(images.pointwise.median, 0.05);
  EXPECT_GE(images.pointwise.within_1db, 0.93);
  EXPECT_LE(exact.averaged.median, 0.2);
  EXPECT_GE(exact.averaged.within_1db, 0.90);
}

TEST(GramField, PekerisLosslessAgainstImagesAndRangeAveragedExactField) { expect_pekeris("pekeris_500hz"); }
TEST(GramField, PekerisLossyAgainstImagesAndRangeAveragedExactField) { expect_pekeris("pekeris_lossy_500hz"); }
TEST(GramField, Pekeris2kHzAgainstImagesAndRangeAveragedExactField) { expect_pekeris("pekeris_2000hz"); }

// Geometric Gaussian beams (spec §4.8.2): the same ray sums, a smoother
// weight with a one-wavelength floor. No README band; held to the hat
// beams' bands where a Gaussian's leak past a boundary does not matter.
TEST(GramField, GaussianBeamsInFreeSpaceAndIncoherentLloydMirror) {
  Environment free = load("free_space.env");
  free.set_beam_shape(GAUSSIAN);
  EXPECT_LE(run(free, "free_space.csv", "tl_db").pointwise.max, 0.05);
  Environment lloyd = load("lloyd_mirror_inc.env");
  lloyd.set_beam_shape(GAUSSIAN);
  EXPECT_LE(run(lloyd, "lloyd_mirror.csv", "tl_incoherent_db").pointwise.median, 0.01);
}

TEST(GramField, IdealRigidWaveguideRangeAveragedAgainstTheModeSum) {
  const Comparison c = run(load("ideal_rigid_500hz.env"), "ideal_rigid_500hz.csv", "tl_exact_db");
  EXPECT_LE(c.averaged.median, 0.6);
  EXPECT_GE(c.averaged.within_3db, 0.95);
}

}  // namespace
}  // namespace acomms::gram
