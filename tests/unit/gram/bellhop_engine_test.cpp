// The external engine: the .env it writes reads back as the same
// environment, the .shd reader takes both layouts, and the engine driven
// through stand-in executables (one writing a known field, one that hangs,
// one that fails) answers, times out or fails with the program's own words.
#include <google/protobuf/util/field_comparator.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "gram/bellhop_engine.h"
#include "gram/bellhop_export.h"
#include "gram/bellhop_import.h"
#include "gram/shd_file.h"

namespace acomms::gram {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

Environment conformance_env(const std::string& name) {
  return import_bellhop_env_file(std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/" + name).environment;
}

Environment small_env() {
  Environment env = conformance_env("pekeris_lossy_500hz.env");
  env.clear_receiver_range_m();
  for (int i = 1; i <= 6; ++i) env.add_receiver_range_m(250.0 * i);
  env.clear_receiver_depth_m();
  for (double z : {10.0, 40.0, 70.0}) env.add_receiver_depth_m(z);
  return env;
}

TEST(GramBellhopExport, EveryConformanceEnvironmentReadsBackUnchanged) {
  for (const auto& entry : fs::directory_iterator(std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs")) {
    if (entry.path().extension() != ".env") continue;
    const Environment env = import_bellhop_env_file(entry.path()).environment;
    const BellhopInput input = export_bellhop(env);
    Environment back =
        import_bellhop_env(input.env, "exported.env", [&](const std::string& ext) -> std::optional<std::string> {
          if (ext == "bty" && input.bty) return *input.bty;
          return std::nullopt;
        }).environment;
    Environment expected = env;
    expected.set_arrivals_run(false);  // TL runs only
    if (expected.title().empty()) expected.set_title("acommsd");
    // Ranges go through km and back: equal to within a few ulps.
    google::protobuf::util::DefaultFieldComparator comparator;
    comparator.set_float_comparison(google::protobuf::util::DefaultFieldComparator::APPROXIMATE);
    comparator.SetDefaultFractionAndMargin(1e-12, 1e-9);
    google::protobuf::util::MessageDifferencer differ;
    differ.set_field_comparator(&comparator);
    std::string report;
    differ.ReportDifferencesToString(&report);
    EXPECT_TRUE(differ.Compare(expected, back)) << entry.path() << ": " << report.substr(0, 2000);
  }
}

ShdField known_field() {
  ShdField f;
  f.title = "known";
  f.plot_type = "rectilin";
  f.freq = {500};
  f.theta = {0};
  f.sx = {0};
  f.sy = {0};
  f.source_depth_m = {20};
  f.receiver_depth_m = {10, 20, 30};
  f.receiver_range_m = {100, 200, 300, 400};
  for (int k = 0; k < 12; ++k) f.pressure.emplace_back(0.001f * (k + 1), -0.0005f * k);
  return f;
}

TEST(GramShdFile, BothLayoutsReadBackTheField) {
  for (ShdLayout layout : {ShdLayout::k2023, ShdLayout::k2022}) {
    const ShdField f = known_field();
    const ShdField back = read_shd(write_shd(f, layout), "known.shd");
    EXPECT_EQ(back.layout, layout);
    EXPECT_EQ(back.title, "known");
    EXPECT_EQ(back.plot_type, "rectilin");
    EXPECT_EQ(back.receiver_range_m, f.receiver_range_m);
    EXPECT_EQ(back.receiver_depth_m, f.receiver_depth_m);
    EXPECT_EQ(back.pressure, f.pressure);
  }
}

TEST(GramShdFile, ATruncatedFileIsRefusedNamingTheRecord) {
  const std::string bytes = write_shd(known_field(), ShdLayout::k2023);
  try {
    // Records of 41 words: record 12 (the last pressure row) starts at byte
    // 12 · 164; cut inside its 4 complex values.
    read_shd(bytes.substr(0, 12 * 164 + 20), "cut.shd");
    FAIL() << "a truncated .shd was read";
  } catch (const ShdError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.shd: record 12"), std::string::npos) << e.what();
  }
}

TEST(GramShdFile, ABadRecordLengthIsRefused) {
  std::string bytes = write_shd(known_field(), ShdLayout::k2023);
  const std::int32_t bad = 3;
  std::memcpy(bytes.data(), &bad, 4);
  EXPECT_THROW(read_shd(bytes, "bad.shd"), ShdError);
}

class BellhopEngineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("bellhop-engine-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string script(const std::string& name, const std::string& body) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
    ::chmod(path.c_str(), 0755);
    return path.string();
  }
  std::unique_ptr<ModelEngine> engine(const std::string& executable, double timeout_s = 20) {
    return make_bellhop_engine({executable, (dir_ / "runs").string(), std::chrono::duration<double>(timeout_s)});
  }
  bool runs_left() const { return fs::exists(dir_ / "runs") && !fs::is_empty(dir_ / "runs"); }

  fs::path dir_;
};

TEST_F(BellhopEngineTest, TheKnownFieldOfTheStandInComesBackAsTlInBothLayouts) {
  for (const char* layout : {"2023", "2022"}) {
    auto e = engine(script(std::string("bellhop_") + layout, std::string("exec ") + FAKE_BELLHOP + " --layout " +
                                                                    layout + " \"$@\""));
    CancelToken token;
    const Environment env = small_env();
    const TransmissionLoss tl = e->transmission_loss(env, token);
    ASSERT_EQ(tl.tl_db.size(), 18u);
    for (int iz = 0; iz < 3; ++iz)
      for (int ir = 0; ir < 6; ++ir)
        EXPECT_NEAR(tl.tl_db[iz * 6 + ir], 20 * std::log10(env.receiver_range_m(ir)) + env.receiver_depth_m(iz) / 10,
                    1e-4)
            << layout << " " << iz << "," << ir;
    EXPECT_FALSE(runs_left()) << "the run directory was not removed";
  }
}

TEST_F(BellhopEngineTest, AFailingEngineIsReportedWithItsOwnWords) {
  auto e = engine(script("bellhop_fails", "echo 'BELLHOP: the bottom is above the source' >&2\nexit 3"));
  CancelToken token;
  try {
    e->transmission_loss(small_env(), token);
    FAIL() << "no error";
  } catch (const EngineError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("exited with status 3"), std::string::npos) << what;
    EXPECT_NE(what.find("BELLHOP: the bottom is above the source"), std::string::npos) << what;
  }
  EXPECT_FALSE(runs_left());
}

TEST_F(BellhopEngineTest, AHangingEngineIsKilledAtTheTimeLimit) {
  auto e = engine(script("bellhop_hangs", "echo started\nexec sleep 600"), 0.3);
  CancelToken token;
  const auto start = std::chrono::steady_clock::now();
  try {
    e->transmission_loss(small_env(), token);
    FAIL() << "no error";
  } catch (const EngineError& error) {
    EXPECT_NE(std::string(error.what()).find("engine_timeout_s = 0.3"), std::string::npos) << error.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 20s);  // bounded, not the sleep's 600 s
  EXPECT_FALSE(runs_left());
}

TEST_F(BellhopEngineTest, CancellingStopsAHangingEngine) {
  auto e = engine(script("bellhop_hangs", "exec sleep 600"), 600);
  CancelToken token;
  std::thread canceller([&] {
    std::this_thread::sleep_for(100ms);  // the cancel arrives mid-run; no ordering is awaited
    token.cancel();
  });
  EXPECT_THROW(e->transmission_loss(small_env(), token), ModelCancelled);
  canceller.join();
}

TEST_F(BellhopEngineTest, AMissingShdIsAnEngineError) {
  auto e = engine(script("bellhop_silent", "echo 'nothing written'"));
  CancelToken token;
  try {
    e->transmission_loss(small_env(), token);
    FAIL() << "no error";
  } catch (const EngineError& error) {
    EXPECT_NE(std::string(error.what()).find("wrote no run.shd: nothing written"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace acomms::gram
