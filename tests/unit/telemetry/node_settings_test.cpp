// acommsd's telemetry section: defaults, refusals that name the field and
// the bound, the telemetry queues it configures, and the datum.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "telemetry/node_settings.h"
#include "telemetry/wire_message.h"

namespace acomms::telemetry {
namespace {

v1::TelemetryConfig parse(const std::string& text) {
  v1::TelemetryConfig config;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &config)) << text;
  return config;
}

std::string refusal(const std::string& text, int32_t own_id = 1) {
  try {
    node_settings(parse(text), own_id);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(NodeSettingsTest, UnsetFieldsAreTheThesisDefaults) {
  const NodeSettings s = node_settings(parse(""), 1);
  EXPECT_EQ(s.stream.tau_s, 10u);
  EXPECT_EQ(s.stream.precision_m, 1);
  EXPECT_EQ(s.stream.innovation_min, -50);
  EXPECT_EQ(s.stream.innovation_max, 51);
  EXPECT_EQ(s.stream.sigma_j2, 1e-3);
  EXPECT_EQ(s.stream.r_m2, 25);
  EXPECT_EQ(s.stream.full_every, 60u);
  EXPECT_EQ(s.stream.speed_mps, 1.5);
  EXPECT_EQ(s.stream.observer, ObserverKind::kKalman);
  EXPECT_EQ(s.stream.model, ModelKind::kLearned);
  EXPECT_EQ(s.ttl_s, 1800);
  EXPECT_EQ(s.gap_timeout_s, 1800);
  EXPECT_TRUE(s.receivers.empty());
  EXPECT_EQ(s.datum, nullptr);
}

TEST(NodeSettingsTest, RefusalsNameTheFieldAndTheBound) {
  EXPECT_EQ(refusal("tau_s: 0"), "telemetry.tau_s must be within [1, 3600] s");
  EXPECT_EQ(refusal("observer: \"psychic\""), "telemetry.observer \"psychic\" is not one of fixed_speed, kalman");
  EXPECT_EQ(refusal("receiver: 1"), "telemetry.receiver 1 is this node's own modem id");
  EXPECT_EQ(refusal("receiver: 200"), "telemetry.receiver 200 must be a modem id within [1, 127]");
  EXPECT_EQ(refusal("receiver: 2 receiver: 2"), "telemetry.receiver 2 is listed twice");
  EXPECT_NE(refusal("tau_s: 1 ttl_s: 2049").find("telemetry.ttl_s 2049.000000 must be within (0, 2048.000000] s"),
            std::string::npos)
      << refusal("tau_s: 1 ttl_s: 2049");
  EXPECT_EQ(refusal("datum { lat: 95 }"), "telemetry.datum.lat 95.000000 must be within [-90, 90]");
  EXPECT_EQ(refusal("region_min_m: 1"), "telemetry.region_min_m needs 3 values (x, y, z)");
}

TEST(NodeSettingsTest, TelemetryQueuesAreAckedOldestFirstAndOutOfTheDuplicateFilter) {
  v1::QueueConfig queues;
  // An operator's own entry for one of them keeps its other settings.
  v1::QueueTypeConfig* own = queues.add_type();
  own->set_type(std::string(kDeltaType));
  own->mutable_policy()->set_value_base(3);
  configure_queues(&queues, node_settings(parse("ttl_s: 900"), 1));
  // The stream's two types and the receiver's feedback to its sender.
  ASSERT_EQ(queues.type_size(), 3);
  EXPECT_EQ(queues.type(2).type(), kFeedbackType);
  for (const v1::QueueTypeConfig& entry : queues.type()) {
    EXPECT_TRUE(entry.policy().ack()) << entry.type();
    EXPECT_FALSE(entry.policy().newest_first()) << entry.type();
    EXPECT_EQ(entry.policy().ttl_s(), 900) << entry.type();
    EXPECT_EQ(entry.roles().source_field(), "src");
    EXPECT_EQ(entry.roles().destination_field(), "dest");
    EXPECT_TRUE(entry.has_duplicate_filter() && !entry.duplicate_filter()) << entry.type();
  }
  EXPECT_EQ(queues.type(0).policy().value_base(), 3);
}

TEST(NodeSettingsTest, DatumTurnsLatLonIntoLocalMetresAndBack) {
  const NodeSettings s = node_settings(parse("datum { lat: 41.5247 lon: -70.6711 }"), 1);
  ASSERT_NE(s.datum, nullptr);
  const LocalXY origin = s.datum->to_local({41.5247, -70.6711});
  EXPECT_NEAR(origin.x, 0, 1e-6);
  EXPECT_NEAR(origin.y, 0, 1e-6);
  // 0.01 degree north is about 1111 m at this latitude (WGS84 meridian arc).
  const LocalXY north = s.datum->to_local({41.5347, -70.6711});
  EXPECT_NEAR(north.x, 0, 1e-6);
  EXPECT_NEAR(north.y, 1110.8, 1.0);
  // 0.01 degree east is cos(lat) of that, on the parallel.
  const LocalXY east = s.datum->to_local({41.5247, -70.6611});
  EXPECT_NEAR(east.x, 834.4, 1.0);
  const LatLon back = s.datum->to_latlon({east.x, east.y});
  EXPECT_NEAR(back.lat, 41.5247, 1e-7);
  EXPECT_NEAR(back.lon, -70.6611, 1e-7);
}

}  // namespace
}  // namespace acomms::telemetry
