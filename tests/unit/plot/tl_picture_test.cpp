// `gram tl --png`'s picture read back pixel by pixel: the colour bar holds
// the colour map at its labelled dB values, and there is text where the
// title, the axes' names and numbers, the colour bar's name and the
// profile's axis are drawn (non-background pixels in each box), set in the
// built-in font, so the picture is the same wherever it is drawn.
#include <gtest/gtest.h>

#include <cmath>

#include "gram_plot.h"
#include "plot/axes.h"

namespace acomms::cli {
namespace {

gram::Environment environment() {
  gram::Environment env;
  env.set_title("test channel");
  env.set_frequency_hz(10000);
  env.set_source_depth_m(20);
  auto* surface = env.add_sound_speed();
  surface->set_depth_m(0);
  surface->set_speed_mps(1500);
  auto* bottom = env.add_sound_speed();
  bottom->set_depth_m(100);
  bottom->set_speed_mps(1520);
  return env;
}

// TL grows with range, 41.3 dB (floored to 41 on the bar) to 100 dB.
gram::TransmissionLoss field() {
  gram::TransmissionLoss tl;
  for (int r = 0; r <= 50; ++r) tl.range_m.push_back(100.0 * r);
  for (int z = 0; z <= 20; ++z) tl.depth_m.push_back(5.0 * z);
  for (std::size_t z = 0; z < tl.depth_m.size(); ++z)
    for (std::size_t r = 0; r < tl.range_m.size(); ++r) tl.tl_db.push_back(41.3 + 58.7 * r / 50.0);
  return tl;
}

// Pixels in [x0, x1] x [y0, y1] that are not white.
int inked(const plot::Canvas& c, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = std::max(0, y0); y <= std::min(c.height() - 1, y1); ++y)
    for (int x = std::max(0, x0); x <= std::min(c.width() - 1, x1); ++x) n += !(c.at(x, y) == plot::kWhite);
  return n;
}

TEST(TlPicture, TheColourBarHoldsTheColourMapAtItsLabelledDbValues) {
  const plot::Canvas c = draw_tl(field(), environment(), "/data/test.env");
  const double best = 41;  // the field's lowest TL, floored
  for (double db : plot::nice_ticks(best, best + 60, 6)) {
    const plot::Rgb want = tl_colour(db, best);
    EXPECT_EQ(c.at(tl_colour_bar_x(), tl_colour_bar_y(db, best)), want) << db << " dB";
  }
  // Loud is red at the top, quiet blue at the bottom.
  const plot::Rgb top = c.at(tl_colour_bar_x(), tl_colour_bar_y(best, best));
  const plot::Rgb bottom = c.at(tl_colour_bar_x(), tl_colour_bar_y(best + 60, best));
  EXPECT_GT(top.r, top.b);
  EXPECT_GT(bottom.b, bottom.r);
  // A field pixel near range 0 has the colour of its TL (41.3 dB).
  EXPECT_EQ(c.at(82, 250), tl_colour(41.3, best));
}

TEST(TlPicture, TextIsWhereTheTitleAxesColourBarAndProfileAreNamed) {
  const plot::Canvas c = draw_tl(field(), environment(), "/data/test.env");
  EXPECT_GT(inked(c, 200, 4, 900, 28), 200) << "title";
  EXPECT_GT(inked(c, 350, 466, 500, 500), 100) << "range ticks and name";
  EXPECT_GT(inked(c, 2, 150, 60, 350), 100) << "depth numbers and name";
  EXPECT_GT(inked(c, 803, 40, 880, 460), 150) << "colour bar numbers and name";
  EXPECT_GT(inked(c, 900, 466, 1090, 505), 100) << "sound speed axis";
  // Where no text goes stays white: between the field's axis name and the
  // bottom edge, away from every label.
  EXPECT_EQ(inked(c, 0, 505, 1099, 519), 0);
}

TEST(TlPicture, TheTitleNamesTheInputFileAndTheLongerTitleTakesMoreRoom) {
  const int short_name = inked(draw_tl(field(), environment(), "a.env"), 0, 4, 1099, 28);
  const int long_name = inked(draw_tl(field(), environment(), "/x/a-much-longer-environment-name.env"), 0, 4, 1099, 28);
  EXPECT_GT(long_name, short_name + 100);
}

TEST(TlPicture, TheSourceAndTheReceiverAreMarkedAtTheirRangeAndDepth) {
  TlMarks marks;
  marks.source = "buoy, node 3";
  marks.receiver = TlReceiver{3000, 60, "node 2, 60 m"};
  const plot::Canvas c = draw_tl(field(), environment(), "/data/test.env", marks);
  const plot::Canvas plain = draw_tl(field(), environment(), "/data/test.env");
  // The source: a black dot ringed in white at range 0 and its depth (20 m).
  const auto [sx, sy] = tl_pixel(field(), environment(), 0, 20);
  EXPECT_EQ(c.at(sx, sy), plot::kBlack);
  EXPECT_EQ(c.at(sx, sy - 6), plot::kWhite);
  // The receiver: a black square ringed in white at 3 km and 60 m, which
  // the picture without it does not have.
  const auto [rx, ry] = tl_pixel(field(), environment(), 3000, 60);
  EXPECT_EQ(rx, 80 + 680 * 3 / 5);
  EXPECT_EQ(ry, 40 + 420 * 60 / 100);
  for (int d : {-4, 0, 4}) EXPECT_EQ(c.at(rx + d, ry + d), kTlReceiverMark) << d;
  EXPECT_EQ(c.at(rx + 6, ry + 6), plot::kWhite);
  EXPECT_EQ(plain.at(rx, ry), tl_colour(41.3 + 58.7 * 30 / 50.0, 41));
  // Its depth across the field: dotted white, on both sides of the mark.
  int white_left = 0, white_right = 0;
  for (int x = 82; x < rx - 10; ++x) white_left += c.at(x, ry) == plot::kWhite;
  for (int x = rx + 10; x < 758; ++x) white_right += c.at(x, ry) == plot::kWhite;
  EXPECT_GT(white_left, 60);
  EXPECT_GT(white_right, 20);
  // Each is labelled: dark text (anti-aliased) on a white ground beside
  // the mark, where the field would be.
  auto label = [&](int x0, int y0) {
    int ground = 0, ink = 0;
    for (int y = y0 - 5; y <= y0 + 5; ++y)
      for (int x = x0; x < x0 + 50; ++x) {
        const plot::Rgb p = c.at(x, y);
        ground += p == plot::kWhite;
        ink += p.r + p.g + p.b < 300;
      }
    return std::pair{ground, ink};
  };
  const auto [source_ground, source_ink] = label(sx + 12, sy);
  const auto [receiver_ground, receiver_ink] = label(rx + 12, ry - 14);
  EXPECT_GT(source_ground, 150);
  EXPECT_GT(source_ink, 30);
  EXPECT_GT(receiver_ground, 150);
  EXPECT_GT(receiver_ink, 30);
}

TEST(TlPicture, TextWidthGrowsWithTheTextAndItsSize) {
  EXPECT_GT(plot::text_width("Range (km)", 14), plot::text_width("Range", 14));
  EXPECT_NEAR(plot::text_width("Range", 28), 2 * plot::text_width("Range", 14), 1.0);
  EXPECT_GT(plot::text_width("Range", 14), 20);
}

TEST(TlPicture, NiceTicksAreWholeStepsInsideTheRange) {
  EXPECT_EQ(plot::nice_ticks(41, 101, 6), (std::vector<double>{50, 60, 70, 80, 90, 100}));
  EXPECT_EQ(plot::nice_ticks(0, 5, 5), (std::vector<double>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(plot::tick_label(0.25, 0.05), "0.25");
  EXPECT_EQ(plot::tick_label(1500, 10), "1500");
}

}  // namespace
}  // namespace acomms::cli

namespace acomms::cli {
namespace {

TEST(ObjectivePicture, TheBestDepthIsARedLineWithItsValueInTheLegend) {
  gram::DepthObjectiveReply reply;
  reply.set_bottom_m(80);
  reply.set_best_depth_m(40);
  for (int z = 0; z <= 100; z += 5) {
    auto* p = reply.add_points();
    p->set_depth_m(z);
    p->set_objective(z / 100.0);
    p->set_objective_filtered(z / 120.0);
  }
  const plot::Canvas c = draw_objective(reply, "Depth objective for test");
  const int y = 40 + static_cast<int>(std::lround(40.0 / 100 * 420));  // the frame's row of 40 m
  EXPECT_EQ(c.at(300, y), kObjectiveBest);
  int ink = 0;
  for (int yy = 95; yy <= 115; ++yy)
    for (int x = 515; x <= 690; ++x) ink += !(c.at(x, yy) == plot::kWhite);
  EXPECT_GT(ink, 100) << "the legend's best depth";
  ink = 0;
  for (int yy = 4; yy <= 28; ++yy)
    for (int x = 0; x < c.width(); ++x) ink += !(c.at(x, yy) == plot::kWhite);
  EXPECT_GT(ink, 150) << "title";
  // No source depth given: none drawn.
  EXPECT_EQ(c.at(300, 40 + static_cast<int>(std::lround(15.0 / 100 * 420))), plot::kWhite);
}

TEST(ObjectivePicture, TheSourceIsADashedBlueLineAtItsDepthWithItsLegend) {
  gram::DepthObjectiveReply reply;
  reply.set_bottom_m(80);
  reply.set_best_depth_m(40);
  for (int z = 0; z <= 100; z += 5) {
    auto* p = reply.add_points();
    p->set_depth_m(z);
    p->set_objective(0.9);
    p->set_objective_filtered(0.95);
  }
  const plot::Canvas c = draw_objective(reply, "Depth objective for test", 15.0);
  const int y = 40 + static_cast<int>(std::lround(15.0 / 100 * 420));
  int dashes = 0, gaps = 0;
  for (int x = 81; x < 460; ++x) (c.at(x, y) == kObjectiveSource ? dashes : gaps) += 1;
  EXPECT_GT(dashes, 150);
  EXPECT_GT(gaps, 60);  // dashed, not solid
  EXPECT_EQ(c.at(482, 148), kObjectiveSource) << "the legend's sample";
  int ink = 0;
  for (int yy = 140; yy <= 156; ++yy)
    for (int x = 518; x <= 690; ++x) ink += !(c.at(x, yy) == plot::kWhite);
  EXPECT_GT(ink, 100) << "the legend's source";
}

}  // namespace
}  // namespace acomms::cli
