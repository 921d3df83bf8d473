// `acommsctl gram` end to end (offline, no daemon): the CLI prints what the
// library computes, draws a PNG, writes a .shd the project's reader reads
// back, and refuses bad input with exit status 1 (unreadable or refused
// file) or 2 (bad usage).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "child_process.h"
#include "gram/bellhop_import.h"
#include "gram/shd_file.h"
#include "gram/transmission_loss.h"

namespace {

using acomms::testing::lines_of;
using acomms::testing::run;

const std::string kEnvs = std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/";

// Where one run's output goes: ctest runs these tests in parallel
// processes, so each needs its own files.
std::string prefix() {
  return ::testing::TempDir() + "gram_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
         std::to_string(::getpid());
}

TEST(AcommsctlGram, SspPrintsTheCastsProfile) {
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "ssp", "--ctd", std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/ctd_cast_to_ssp.csv"}, prefix());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = lines_of(r.out);
  ASSERT_GE(out.size(), 3u);
  EXPECT_EQ(out[0], "depth_m,speed_mps");
  EXPECT_EQ(out[1].rfind("0.000,", 0), 0u) << out[1];
}

TEST(AcommsctlGram, SspThinningKeepsFewerPointsWithTheSameEnds) {
  const std::string cast = std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/ctd_cast_to_ssp.csv";
  const auto all = run(ACOMMSCTL_BINARY, {"gram", "ssp", "--ctd", cast}, prefix());
  const auto thin = run(ACOMMSCTL_BINARY, {"gram", "ssp", "--ctd", cast, "--thin", "0.5"}, prefix());
  ASSERT_EQ(thin.exit_code, 0) << thin.err;
  const auto a = lines_of(all.out), t = lines_of(thin.out);
  EXPECT_LT(t.size(), a.size());
  EXPECT_EQ(t.at(1), a.at(1));
  EXPECT_EQ(t.back(), a.back());
}

TEST(AcommsctlGram, TlPrintsOneCsvRowPerReceiverAndReportsTheAutomaticBeamCount) {
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", kEnvs + "lloyd_mirror.env"}, prefix());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = lines_of(r.out);
  EXPECT_EQ(out.at(0), "range_m,depth_m,tl_db");
  EXPECT_EQ(out.size(), 1u + 100u * 99u);  // 100 depths × 99 ranges
  EXPECT_NE(r.err.find("500 beams (automatic"), std::string::npos) << r.err;
}

// A Lloyd-mirror field of 201 depths × 200 ranges: enough rows (40,200) for
// acommsctl to split the formatting across threads.
std::string lloyd_field_env(const std::string& prefix) {
  const std::string path = prefix + ".env";
  std::ofstream(path) << "'Lloyd mirror, 201 x 200'\n500\n1\n'CVW'\n0 0.0 1000\n0 1500 /\n1000 1500 /\n"
                         "'A' 0.0\n1000 1500 0 1 0 0.0 /\n1\n50 /\n201\n0 200 /\n200\n0.025 5 /\n'CG'\n0\n"
                         "-89 89 /\n0 1001 5.1\n";
  return path;
}

struct CsvRow {
  double range_m, depth_m;
  std::string tl;
};

std::vector<CsvRow> csv_rows(const std::string& text) {
  std::vector<CsvRow> rows;
  const auto lines = lines_of(text);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    char* end = nullptr;
    CsvRow row;
    row.range_m = std::strtod(lines[i].c_str(), &end);
    EXPECT_EQ(*end, ',') << lines[i];
    row.depth_m = std::strtod(end + 1, &end);
    EXPECT_EQ(*end, ',') << lines[i];
    row.tl = end + 1;
    rows.push_back(row);
  }
  return rows;
}

TEST(AcommsctlGram, TlCsvIsTheSameBytesOnOneTwoAndThreeThreads) {
  const std::string env = lloyd_field_env(prefix());
  const auto one = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", env, "--threads", "1"}, prefix() + "_1");
  const auto two = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", env, "--threads", "2"}, prefix() + "_2");
  const auto three = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", env, "--threads", "3"}, prefix() + "_3");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_EQ(lines_of(one.out).size(), 1u + 201u * 200u);
  EXPECT_TRUE(two.out == one.out) << "2 threads differ from 1";
  EXPECT_TRUE(three.out == one.out) << "3 threads differ from 1";
}

TEST(AcommsctlGram, TlCsvPrintsRangesAndDepthsExactly) {
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", lloyd_field_env(prefix())}, prefix());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("e+"), std::string::npos) << "a coordinate printed in exponent form";
  const auto rows = csv_rows(r.out);
  ASSERT_EQ(rows.size(), 201u * 200u);
  // Depth-major: row 200 · 150 + 55 is depth 150 m, range 25 + 55 · 25 m.
  EXPECT_NEAR(rows[200 * 150 + 55].depth_m, 150.0, 1e-9);
  EXPECT_NEAR(rows[200 * 150 + 55].range_m, 1400.0, 1e-9);
  EXPECT_NEAR(rows[200 * 150 + 199].range_m, 5000.0, 1e-9);
}

// The CSV against the library's own run of the same file: coordinates
// exactly, TL as printf("%.3f") prints the model's double (so within half
// a thousandth of it), empty on the source axis, `inf` in shadow.
TEST(AcommsctlGram, TlCsvValuesAreTheModelsFieldToTheThousandth) {
  const std::string env_file = lloyd_field_env(prefix());
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", env_file, "--threads", "2"}, prefix());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  acomms::gram::RunOptions options;
  options.threads = 1;
  const auto field =
      acomms::gram::compute_transmission_loss(acomms::gram::import_bellhop_env_file(env_file).environment, options);
  const auto rows = csv_rows(r.out);
  ASSERT_EQ(rows.size(), field.tl_db.size());
  const std::size_t nr = field.range_m.size();
  int finite = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].range_m, field.range_m[i % nr]) << "row " << i;
    ASSERT_EQ(rows[i].depth_m, field.depth_m[i / nr]) << "row " << i;
    const double tl = field.tl_db[i];
    if (std::isnan(tl)) {
      ASSERT_EQ(rows[i].tl, "") << "row " << i;
    } else if (std::isinf(tl)) {
      ASSERT_EQ(rows[i].tl, "inf") << "row " << i;
    } else {
      char text[400];
      std::snprintf(text, sizeof text, "%.3f", tl);
      ASSERT_EQ(rows[i].tl, text) << "row " << i;
      ASSERT_LE(std::abs(std::stod(rows[i].tl) - tl), 0.0005 * (1 + 1e-12)) << "row " << i;
      ++finite;
    }
  }
  EXPECT_GT(finite, 40000);
}

TEST(AcommsctlGram, TlRefusesAnUnknownFormatNamingTheChoices) {
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", kEnvs + "lloyd_mirror.env", "--format", "mat"}, prefix());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << "no field is written";
  EXPECT_NE(r.err.find("--format"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mat"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("shd"), std::string::npos) << r.err;
}

TEST(AcommsctlGram, TlShdReadsBackAsTheCsvsCoordinatesAndValues) {
  const std::string env = lloyd_field_env(prefix());
  const auto csv = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", env}, prefix() + "_csv");
  const auto shd = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", env, "--format", "shd"}, prefix() + "_shd");
  ASSERT_EQ(shd.exit_code, 0) << shd.err;
  const auto field = acomms::gram::read_shd(shd.out, "acommsctl.shd");
  EXPECT_EQ(field.layout, acomms::gram::ShdLayout::k2023);
  EXPECT_EQ(field.freq, std::vector<double>{500.0});
  EXPECT_EQ(field.source_depth_m, std::vector<float>{50.0f});
  const auto rows = csv_rows(csv.out);
  const std::size_t nr = field.receiver_range_m.size();
  ASSERT_EQ(nr, 200u);
  ASSERT_EQ(field.receiver_depth_m.size(), 201u);
  ASSERT_EQ(field.pressure.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(field.receiver_range_m[i % nr], rows[i].range_m) << "row " << i;  // float64 and exact text
    ASSERT_EQ(field.receiver_depth_m[i / nr], static_cast<float>(rows[i].depth_m)) << "row " << i;
    const double magnitude = std::abs(std::complex<double>(field.pressure[i]));
    if (rows[i].tl == "inf") {
      EXPECT_EQ(magnitude, 0.0) << "row " << i;
      continue;
    }
    // The CSV's TL has three decimals; the file's float32 adds 1e-5 dB.
    ASSERT_NEAR(-20.0 * std::log10(magnitude), std::stod(rows[i].tl), 0.0005 + 1e-4) << "row " << i;
  }
}

TEST(AcommsctlGram, TlShdRefusesAnIrregularGridAndAPngBesideIt) {
  const std::string env = prefix() + ".env";
  std::ofstream(env) << "'irregular'\n500\n1\n'CVW'\n0 0.0 1000\n0 1500 /\n1000 1500 /\n"
                        "'A' 0.0\n1000 1500 0 1 0 0.0 /\n1\n50 /\n2\n20 40 /\n2\n1 2 /\n'CG RI'\n0\n"
                        "-89 89 /\n0 1001 2.1\n";
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", env, "--format", "shd"}, prefix());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--format shd: a .shd is written for a rectilinear receiver grid only"), std::string::npos)
      << r.err;
  const auto both = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", env, "--format", "shd", "--png", prefix() + ".png"},
                        prefix() + "_both");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("excludes"), std::string::npos) << both.err;
}

TEST(AcommsctlGram, TlDrawsAPng) {
  const std::string png = prefix() + ".png";
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", kEnvs + "pekeris_2000hz.env", "--png", png}, prefix());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(png, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST(AcommsctlGram, ArrivalsPrintsTheArrivalsAndTheDelaySpread) {
  const auto r = run(ACOMMSCTL_BINARY, {"gram", "arrivals", "--env", kEnvs + "pekeris_lossy_500hz.env", "--at", "500,20"}, prefix());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = lines_of(r.out);
  EXPECT_EQ(out.at(0), "delay_s,amplitude,phase_deg,launch_deg,arrival_deg,n_surface,n_bottom");
  EXPECT_EQ(out.at(1).rfind("0.3335", 0), 0u) << out.at(1);  // the direct path: 500.26 m / 1500 m/s
  EXPECT_EQ(out.back().rfind("# rms_delay_spread_s=", 0), 0u) << out.back();
}

TEST(AcommsctlGram, RefusesBadInputWithAMessage) {
  auto r = run(ACOMMSCTL_BINARY, {"gram", "arrivals", "--env", kEnvs + "pekeris_lossy_500hz.env", "--at", "500"}, prefix());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("give RANGE_M,DEPTH_M"), std::string::npos) << r.err;
  r = run(ACOMMSCTL_BINARY, {"gram", "tl", "--env", "/nonexistent/x.env"}, prefix());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/nonexistent/x.env: cannot be read"), std::string::npos) << r.err;
}

}  // namespace
