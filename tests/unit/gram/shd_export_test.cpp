// The model's field written as a .shd: read back by the project's reader
// with the same coordinates and values (to float32 rounding, as the format
// stores them), in BELLHOP's phase convention, with the header laid out as
// spec §7.5 states (checked byte by byte here, not through the reader).
#include "gram/shd_export.h"

#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <numbers>

#include <gtest/gtest.h>

#include "gram/bellhop_import.h"
#include "gram/transmission_loss.h"

namespace acomms::gram {
namespace {

Environment conformance_env(const std::string& name) {
  return import_bellhop_env_file(std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/" + name).environment;
}

// Free space at 1 kHz (source 1000 m), on a smaller grid that includes the
// source axis's range 0 and a range that is not a float.
Environment free_space() {
  Environment env = conformance_env("free_space.env");
  env.clear_receiver_range_m();
  for (double r : {0.0, 500.0, 1395.97, 2000.0, 3000.0}) env.add_receiver_range_m(r);
  env.clear_receiver_depth_m();
  for (double z : {700.0, 1000.1, 1300.0}) env.add_receiver_depth_m(z);
  env.set_box_range_m(3100);
  return env;
}

template <typename T>
T at(const std::string& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

TEST(GramShdExport, ReadsBackWithTheRunsCoordinatesAndValues) {
  const Environment env = free_space();
  RunOptions options;
  options.keep_pressure = true;
  const TransmissionLoss tl = compute_transmission_loss(env, options);
  const ShdField back = read_shd(write_shd(shd_field_of(tl, env), ShdLayout::k2023), "free.shd");
  EXPECT_EQ(back.layout, ShdLayout::k2023);
  EXPECT_EQ(back.title, env.title());
  EXPECT_EQ(back.plot_type, "rectilin");
  EXPECT_EQ(back.freq, std::vector<double>{1000.0});
  EXPECT_EQ(back.receiver_range_m, tl.range_m);  // float64: exact
  ASSERT_EQ(back.receiver_depth_m.size(), tl.depth_m.size());
  for (std::size_t i = 0; i < tl.depth_m.size(); ++i)
    EXPECT_EQ(back.receiver_depth_m[i], static_cast<float>(tl.depth_m[i]));  // float32, as stored
  EXPECT_EQ(back.source_depth_m, std::vector<float>{1000.0f});
  ASSERT_EQ(back.pressure.size(), tl.tl_db.size());
  for (std::size_t i = 0; i < tl.tl_db.size(); ++i) {
    const double magnitude = std::abs(std::complex<double>(back.pressure[i]));
    if (std::isnan(tl.tl_db[i])) {
      EXPECT_EQ(magnitude, 0.0) << "receiver " << i << " at range 0 has no value";
      continue;
    }
    // float32 keeps 24 bits: 1e-6 relative is 1e-5 dB.
    EXPECT_NEAR(-20.0 * std::log10(magnitude), tl.tl_db[i], 1e-4) << "receiver " << i;
  }
}

TEST(GramShdExport, WritesMinusTheConjugateOfOurPressureAsBellhopDoes) {
  const Environment env = free_space();
  RunOptions options;
  options.keep_pressure = true;
  const TransmissionLoss tl = compute_transmission_loss(env, options);
  const ShdField field = shd_field_of(tl, env);
  const double k = 2 * std::numbers::pi * 1000.0 / 1500.0;
  const std::size_t nr = tl.range_m.size();
  int checked = 0;
  for (std::size_t iz = 0; iz < tl.depth_m.size(); ++iz)
    for (std::size_t ir = 1; ir < nr; ++ir) {
      const double range = std::hypot(tl.range_m[ir], tl.depth_m[iz] - 1000.0);
      // Ours: exp(ikR)/R; BELLHOP's file: −exp(−ikR)/R (spec §0).
      const std::complex<double> bellhop = -std::exp(std::complex<double>(0, -k * range)) / range;
      const std::complex<double> written(field.pressure[iz * nr + ir]);
      EXPECT_LT(std::abs(written - bellhop) / std::abs(bellhop), 0.02) << "at " << tl.range_m[ir] << " m, "
                                                                       << tl.depth_m[iz] << " m";
      ++checked;
    }
  EXPECT_EQ(checked, 12);
}

TEST(GramShdExport, AnIncoherentRunWritesTheRootOfItsIntensityReal) {
  Environment env = free_space();
  env.set_field_mode(INCOHERENT);
  RunOptions options;
  options.keep_pressure = true;
  const TransmissionLoss tl = compute_transmission_loss(env, options);
  const ShdField field = shd_field_of(tl, env);
  for (std::size_t i = 0; i < tl.tl_db.size(); ++i) {
    if (std::isnan(tl.tl_db[i])) continue;
    EXPECT_EQ(field.pressure[i].imag(), 0.0f);
    EXPECT_GT(field.pressure[i].real(), 0.0f);
    EXPECT_NEAR(-20.0 * std::log10(field.pressure[i].real()), tl.tl_db[i], 1e-4);
  }
}

// Spec §7.5, 2023+ layout: records of LRecl words; record 0 LRecl and the
// title, 1 PlotType, 2 seven int32 counts then float64 freq0 and atten,
// 3 freqVec, 4 theta, 5 Sx, 6 Sy (float64), 7 Sz, 8 Rz (float32), 9 Rr
// (float64, metres), 10 + iz the complex64 pressure of depth iz.
TEST(GramShdExport, TheHeaderIsLaidOutAsTheSpecStates) {
  const Environment env = free_space();
  RunOptions options;
  options.keep_pressure = true;
  const TransmissionLoss tl = compute_transmission_loss(env, options);
  const ShdField field = shd_field_of(tl, env);
  const std::string bytes = write_shd(field, ShdLayout::k2023);
  const std::int32_t lrecl = at<std::int32_t>(bytes, 0);
  EXPECT_EQ(lrecl, 41);  // max(41, 2·NRr = 10, NRz = 3, ...)
  const std::size_t record = 4 * static_cast<std::size_t>(lrecl);
  EXPECT_EQ(bytes.size(), (10 + 3) * record);
  std::string title = bytes.substr(4, 80);
  EXPECT_EQ(title.substr(0, env.title().size()), env.title());
  EXPECT_EQ(title.find_first_not_of(' ', env.title().size()), std::string::npos);  // blank-padded
  EXPECT_EQ(bytes.substr(record, 10), "rectilin  ");
  const std::int32_t counts[7] = {1, 1, 1, 1, 1, 3, 5};  // Nfreq Ntheta NSx NSy NSz NRz NRr
  for (int i = 0; i < 7; ++i) EXPECT_EQ(at<std::int32_t>(bytes, 2 * record + 4 * i), counts[i]) << "count " << i;
  EXPECT_EQ(at<double>(bytes, 2 * record + 28), 1000.0);  // freq0
  EXPECT_EQ(at<double>(bytes, 2 * record + 36), 0.0);     // atten
  EXPECT_EQ(at<double>(bytes, 3 * record), 1000.0);       // freqVec
  EXPECT_EQ(at<double>(bytes, 4 * record), 0.0);          // theta
  EXPECT_EQ(at<double>(bytes, 5 * record), 0.0);          // Sx
  EXPECT_EQ(at<double>(bytes, 6 * record), 0.0);          // Sy
  EXPECT_EQ(at<float>(bytes, 7 * record), 1000.0f);       // Sz
  EXPECT_EQ(at<float>(bytes, 8 * record + 4), 1000.1f);   // Rz[1]
  EXPECT_EQ(at<double>(bytes, 9 * record + 2 * 8), 1395.97);  // Rr[2], metres
  // Record 10 + 1 (depth 1000.1 m), range 500 m: re, im as float32.
  const std::complex<float> p(at<float>(bytes, 11 * record + 8), at<float>(bytes, 11 * record + 12));
  EXPECT_EQ(p, field.pressure[1 * 5 + 1]);
  EXPECT_NEAR(std::abs(p), 1.0 / 500.0, 1e-5);
}

TEST(GramShdExport, RefusesIrregularReceiversAndARunWithoutPressure) {
  Environment env = free_space();
  TransmissionLoss tl = compute_transmission_loss(env);  // keep_pressure off
  EXPECT_THROW(shd_field_of(tl, env), std::invalid_argument);
  env.set_irregular_receivers(true);
  env.clear_receiver_depth_m();
  for (int i = 0; i < 5; ++i) env.add_receiver_depth_m(800 + 10 * i);
  RunOptions options;
  options.keep_pressure = true;
  tl = compute_transmission_loss(env, options);
  try {
    shd_field_of(tl, env);
    FAIL() << "an irregular field was written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("irregular"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace acomms::gram
