// A calibration of a (fake) Micro-Modem log: two real acommsd processes on
// fake Micro-Modems 300 m apart; the vehicle (node 1) has
// driver.micromodem.prediction and a GRAM environment, so every packet it
// hears from the topside (node 2) gets, in its "packet" event, the SNR the
// modem measured ($CACST) and the model's prediction (TL and SL − TL − NL);
// `acommsctl link calibrate` on that log recovers the offset planted
// between the two.
//
// The fake's world (tests/fakes/micromodem/README.md, 17): a sound pressure
// level of 185 − 20 log10(range) dB over a noise of 85 dB, so its SNR in is
// 100 − 20 log10(300) = 50.5 dB here. The daemon's model: free space (the
// surface and bottom half-spaces are water itself, so nothing reflects; no
// volume attenuation; incoherent TL), so its TL is spherical spreading too,
// 49.5 dB at 300 m; the noise 85 dB, as the fake's; but a source level of
// 190 dB, 5 dB above the fake's 185. The planted offset, measured −
// predicted, is −5 dB: calibrate must print excess_loss_db 5 (±1, the
// model's beams against the exact spreading). Every packet decodes at one
// fixed range, so the reception curve is refused (no packet was lost, and
// the fake's modems never move: it cannot produce a curve).
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <regex>
#include <string>

#include "micromodem_network.h"

namespace acomms::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kTimeScale = 4;

constexpr const char* kGram = R"(gram {
  base {
    frequency_hz: 25000
    sound_speed { depth_m: 0 speed_mps: 1500 }
    sound_speed { depth_m: 100 speed_mps: 1500 }
    surface { kind: HALF_SPACE half_space { speed_mps: 1500 density_ratio: 1 } }
    bottom { kind: HALF_SPACE half_space { speed_mps: 1500 density_ratio: 1 } }
    field_mode: INCOHERENT
    beam_count: 400
    launch_angle_min_deg: -80
    launch_angle_max_deg: 80
  }
})";

constexpr const char* kPrediction =
    "prediction { source_level_db: 190 noise_level_db: 85 max_range_m: 1000 range_step_m: 10"
    " fixed { modem: 1 position { x: 300 y: 0 z: -10 } } fixed { modem: 2 position { x: 0 y: 0 z: -10 } } }";

v1::EventsResponse packet_events(MicroModemNetwork& net, int id, const std::string& name, std::string* text) {
  RunResult listed = run(ACOMMSCTL_BINARY, {"--socket", net.socket(id), "events", "--kind", "packet", "--json"},
                         (net.dir() / name).string());
  v1::EventsResponse events;
  *text = listed.out.substr(0, 3000) + listed.err;
  if (listed.exit_code == 0) (void)google::protobuf::util::JsonStringToMessage(listed.out, &events);
  return events;
}

int predicted(const v1::EventsResponse& events) {
  int n = 0;
  for (const auto& e : events.events()) n += e.link().has_predicted_snr_db() && e.link().has_snr_in_db() ? 1 : 0;
  return n;
}

TEST(MicroModemCalibration, PacketEventsCarryThePredictionAndCalibrateRecoversThePlantedOffset) {
  MicroModemNetwork net("mm-calibration", {{1, "1,mm2,300,0,0"}, {2, "2,mm2,0,0,0"}}, kTimeScale);
  ASSERT_TRUE(net.ok()) << net.fake_output();
  const std::string mac = "name: \"fixed\" slot { src: 1 rate: 0 seconds: 3 } slot { src: 2 rate: 0 seconds: 3 }";
  net.write_config(1, mac, kPrediction, kGram);
  net.write_config(2, mac);
  for (int id : {1, 2}) ASSERT_TRUE(net.start(id)) << net.daemon_log(id);

  // The Micro-Modem driver sends no cycle with nothing queued: enough
  // Commands for every slot of the topside's to carry a packet, 11 of them
  // with a prediction.
  for (int seq = 1; seq <= 60; ++seq) ASSERT_TRUE(net.submit_command(2, 1, seq).ok());
  v1::EventsResponse events;
  std::string listed;
  const bool enough = wait_until(
      [&] {
        events = packet_events(net, 1, "events", &listed);
        return predicted(events) >= 11;
      },
      150s, 1s);
  ASSERT_TRUE(enough) << predicted(events) << " predicted packets of " << events.events_size() << "\n"
                      << listed << "\nvehicle:\n" << net.daemon_log(1) << "\ntopside:\n" << net.daemon_log(2);
  for (const auto& e : events.events()) {
    if (!e.link().has_predicted_snr_db()) continue;  // the first, before the model's grid came
    EXPECT_EQ(e.link().transmission_src(), 2);
    EXPECT_TRUE(e.link().decoded());
    EXPECT_NEAR(e.link().snr_in_db(), 50.5, 0.05) << "the fake's 100 - 20 log10(300)";
    EXPECT_NEAR(e.link().predicted_tl_db(), 20 * std::log10(300.0), 1.0);
    EXPECT_NEAR(e.link().predicted_snr_db(), 190 - e.link().predicted_tl_db() - 85, 1e-9);
  }

  RunResult calibrated = run(ACOMMSCTL_BINARY, {"--socket", net.socket(1), "link", "calibrate"},
                             (net.dir() / "calibrate").string());
  EXPECT_EQ(calibrated.exit_code, 0) << calibrated.out << calibrated.err;
  std::smatch found;
  ASSERT_TRUE(std::regex_search(calibrated.out, found, std::regex(R"(excess_loss_db: (-?[0-9.]+))")))
      << calibrated.out;
  EXPECT_NEAR(std::stod(found[1]), 5.0, 1.0) << calibrated.out;
  EXPECT_NE(calibrated.out.find("link from modem 2"), std::string::npos) << calibrated.out;
  EXPECT_NE(calibrated.out.find("reception curve: not fitted: "), std::string::npos) << calibrated.out;
  std::printf("%s", calibrated.out.c_str());  // the figures, for the log

  for (int id : {1, 2}) {
    net.daemon(id).signal(SIGTERM);
    EXPECT_EQ(net.daemon(id).wait(15s), std::optional<int>(0)) << "node " << id << ":\n" << net.daemon_log(id);
  }
}

// The same network, the fake's modems losing 30% of the frames they hear
// ($CAMSG,BAD_CRC in place of the frame's $CARXD, $CACST mode 1). At rate 0
// a packet is one frame and carries no header: the driver names its sender
// from the cycle-init heard just before it, so each damaged packet becomes
// a packet event, not decoded, with the $CACST's figures and the model's
// prediction; calibrate counts them among the packets of the reception
// curve's data (its rate line).
TEST(MicroModemCalibration, DamagedPacketsAreLostPacketEventsWithThePredictionAndCalibrateCountsThem) {
  MicroModemNetwork net("mm-calibration-lost", {{1, "1,mm2,300,0,0"}, {2, "2,mm2,0,0,0"}}, kTimeScale,
                        {"--frame-errors", "0.3", "--seed", "5"});
  ASSERT_TRUE(net.ok()) << net.fake_output();
  const std::string mac = "name: \"fixed\" slot { src: 1 rate: 0 seconds: 3 } slot { src: 2 rate: 0 seconds: 3 }";
  net.write_config(1, mac, kPrediction, kGram);
  net.write_config(2, mac);
  for (int id : {1, 2}) ASSERT_TRUE(net.start(id)) << net.daemon_log(id);
  for (int seq = 1; seq <= 60; ++seq) ASSERT_TRUE(net.submit_command(2, 1, seq).ok());

  auto count = [](const v1::EventsResponse& events, bool decoded) {
    int n = 0;
    for (const auto& e : events.events()) {
      n += e.link().has_predicted_snr_db() && e.link().decoded() == decoded ? 1 : 0;
    }
    return n;
  };
  v1::EventsResponse events;
  std::string listed;
  const bool enough = wait_until(
      [&] {
        events = packet_events(net, 1, "events", &listed);
        return count(events, false) >= 3 && count(events, true) >= 5;
      },
      150s, 1s);
  ASSERT_TRUE(enough) << count(events, false) << " lost and " << count(events, true) << " decoded with a prediction\n"
                      << listed << "\nvehicle:\n" << net.daemon_log(1);
  for (const auto& e : events.events()) {
    if (e.link().decoded() || !e.link().has_predicted_snr_db()) continue;
    EXPECT_EQ(e.link().transmission_src(), 2) << "named by its cycle-init";
    EXPECT_EQ(e.link().rate(), 0);
    EXPECT_EQ(e.link().bad_frames(), 1u);
    EXPECT_NEAR(e.link().snr_in_db(), 50.5, 0.05) << "a damaged packet's $CACST figures are kept";
    EXPECT_NEAR(e.link().predicted_tl_db(), 20 * std::log10(300.0), 1.0);
  }

  RunResult calibrated = run(ACOMMSCTL_BINARY, {"--socket", net.socket(1), "link", "calibrate"},
                             (net.dir() / "calibrate").string());
  std::smatch found;
  ASSERT_TRUE(std::regex_search(calibrated.out, found, std::regex(R"(rate 0: ([0-9]+) packets, ([0-9]+) decoded)")))
      << calibrated.out << calibrated.err;
  const int packets = std::stoi(found[1]), decoded = std::stoi(found[2]);
  EXPECT_GE(packets - decoded, 3) << "the lost packets reach the reception curve's data\n" << calibrated.out;
  std::printf("%s", calibrated.out.c_str());

  for (int id : {1, 2}) {
    net.daemon(id).signal(SIGTERM);
    EXPECT_EQ(net.daemon(id).wait(15s), std::optional<int>(0)) << "node " << id << ":\n" << net.daemon_log(id);
  }
}

}  // namespace
}  // namespace acomms::testing
