// `acommsctl gram` end to end (offline, no daemon): the CLI prints what the
// library computes, draws a PNG, and refuses bad input with exit status 1
// (unreadable or refused file) or 2 (bad usage).
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "child_process.h"

namespace {

using acomms::testing::run;

const std::string kEnvs = std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/";

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(AcommsctlGram, SspPrintsTheCastsProfile) {
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "ssp", "--ctd", std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/ctd_cast_to_ssp.csv"}, "gram");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = lines(r.out);
  ASSERT_GE(out.size(), 3u);
  EXPECT_EQ(out[0], "depth_m,speed_mps");
  EXPECT_EQ(out[1].rfind("0.000,", 0), 0u) << out[1];
}

TEST(AcommsctlGram, SspThinningKeepsFewerPointsWithTheSameEnds) {
  const std::string cast = std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/ctd_cast_to_ssp.csv";
  const auto all = run(ACOMMSCTL_BINARY, {"gram", "ssp", "--ctd", cast}, "gram");
  const auto thin = run(ACOMMSCTL_BINARY, {"gram", "ssp", "--ctd", cast, "--thin", "0.5"}, "gram");
  ASSERT_EQ(thin.exit_code, 0) << thin.err;
  const auto a = lines(all.out), t = lines(thin.out);
  EXPECT_LT(t.size(), a.size());
  EXPECT_EQ(t.at(1), a.at(1));
  EXPECT_EQ(t.back(), a.back());
}

TEST(AcommsctlGram, TlPrintsOneCsvRowPerReceiverAndReportsTheAutomaticBeamCount) {
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", kEnvs + "lloyd_mirror.env"}, "gram");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = lines(r.out);
  EXPECT_EQ(out.at(0), "range_m,depth_m,tl_db");
  EXPECT_EQ(out.size(), 1u + 100u * 99u);  // 100 depths × 99 ranges
  EXPECT_NE(r.err.find("500 beams (automatic"), std::string::npos) << r.err;
}

TEST(AcommsctlGram, TlDrawsAPng) {
  const std::string png = ::testing::TempDir() + "/gram_tl.png";
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", kEnvs + "pekeris_2000hz.env", "--png", png}, "gram");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(png, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST(AcommsctlGram, ArrivalsPrintsTheArrivalsAndTheDelaySpread) {
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "arrivals", "--env", kEnvs + "pekeris_lossy_500hz.env", "--at", "500,20"}, "gram");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = lines(r.out);
  EXPECT_EQ(out.at(0), "delay_s,amplitude,phase_deg,launch_deg,arrival_deg,n_surface,n_bottom");
  EXPECT_EQ(out.at(1).rfind("0.3335", 0), 0u) << out.at(1);  // the direct path: 500.26 m / 1500 m/s
  EXPECT_EQ(out.back().rfind("# rms_delay_spread_s=", 0), 0u) << out.back();
}

TEST(AcommsctlGram, RefusesBadInputWithAMessage) {
  auto r = run(ACOMMSCTL_BINARY, {"gram", "arrivals", "--env", kEnvs + "pekeris_lossy_500hz.env", "--at", "500"}, "gram");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("give RANGE_M,DEPTH_M"), std::string::npos) << r.err;
  r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", "/nonexistent/x.env"}, "gram");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/nonexistent/x.env: cannot be read"), std::string::npos) << r.err;
}

}  // namespace
