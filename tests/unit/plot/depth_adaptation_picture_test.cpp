// `sim depth-adaptation --png`'s picture read back: each strategy's line is
// drawn in its colour, the legend shows each colour beside a name (ink),
// and the title and axes carry text.
#include <gtest/gtest.h>

#include "depth_adaptation_plot.h"

namespace acomms::cli {
namespace {

eval::DepthAdaptationResult result() {
  eval::DepthAdaptationResult r;
  r.bin_edges_m = {0, 1000, 2000, 3000};
  for (const char* name : {"10 m", "30 m", "50 m", "adaptive"}) {
    eval::StrategyResult s;
    s.name = name;
    s.sent = {10, 10, 10};
    s.received = {9, 5, 1};
    r.strategies.push_back(s);
  }
  r.strategies.back().received = {10, 8, 6};
  return r;
}

int inked(const plot::Canvas& c, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) n += !(c.at(x, y) == plot::kWhite);
  return n;
}

TEST(DepthAdaptationPicture, TheLegendShowsEachStrategysColourBesideItsName) {
  const eval::DepthAdaptationResult r = result();
  const plot::Canvas c = draw_depth_adaptation(r, "/x/glint10.env", 30);
  for (std::size_t s = 0; s < r.strategies.size(); ++s) {
    EXPECT_EQ(c.at(legend_x(), legend_y(s)), strategy_colour(r, s)) << r.strategies[s].name;
    EXPECT_GT(inked(c, legend_x() + 25, legend_y(s) - 8, legend_x() + 120, legend_y(s) + 8), 40) << r.strategies[s].name;
  }
  EXPECT_EQ(strategy_colour(r, 3), plot::kBlack);  // adaptive
  EXPECT_NE(strategy_colour(r, 0), strategy_colour(r, 2));
}

TEST(DepthAdaptationPicture, TitleAndAxesCarryText) {
  const plot::Canvas c = draw_depth_adaptation(result(), "/x/glint10.env", 30);
  EXPECT_GT(inked(c, 100, 4, 800, 28), 200) << "title";
  EXPECT_GT(inked(c, 300, 456, 500, 495), 100) << "range axis";
  EXPECT_GT(inked(c, 2, 100, 75, 400), 100) << "probability axis";
  EXPECT_EQ(inked(c, 0, 500, 899, 519), 0);
}

TEST(DepthAdaptationPicture, TheSourceAndTheReceiverAreNamedUnderTheLegend) {
  const eval::DepthAdaptationResult r = result();
  const plot::Canvas c = draw_depth_adaptation(r, "/x/glint10.env", 30);
  const int y = nodes_note_y(r.strategies.size());
  EXPECT_GT(y, legend_y(r.strategies.size() - 1) + 10);  // below the last strategy
  EXPECT_GT(inked(c, 730, y - 7, 899, y + 7), 150) << "source: the buoy";
  EXPECT_GT(inked(c, 730, y + 11, 899, y + 41), 250) << "receiver: the vehicle";
  // The buoy's depth is in the note: another depth, other pixels.
  const plot::Canvas other = draw_depth_adaptation(r, "/x/glint10.env", 75);
  int differ = 0;
  for (int yy = y - 7; yy <= y + 7; ++yy)
    for (int x = 730; x < 900; ++x) differ += !(c.at(x, yy) == other.at(x, yy));
  EXPECT_GT(differ, 10);
}

}  // namespace
}  // namespace acomms::cli
