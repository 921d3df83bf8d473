#include "gateway_fleet.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "daemon_config.h"
#include "iridium_vehicle_link.h"

namespace acomms::testing {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

const std::string kImei = "300234010000001";
const std::string kExampleProto = std::string(ACOMMS_SOURCE_DIR) + "/examples/messages.proto";

// A plan for a vehicle, larger than a Command, of a type the buoy never
// loads: its bytes must cross the buoy as they are.
constexpr const char* kSurveyPlanProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package fleet;
message SurveyPlan {
  option (dccl.msg) = { codec_version: 4 id: 40 max_bytes: 48 };
  required int32 src = 1 [(dccl.field) = { min: 0 max: 31 }];
  required int32 dest = 2 [(dccl.field) = { min: 0 max: 31 }];
  required double time = 3 [(dccl.field).codec = "dccl.time"];
  required uint32 plan = 4 [(dccl.field) = { min: 0 max: 65535 }];
  required double x0 = 5 [(dccl.field) = { min: -10000 max: 10000 precision: 1 }];
  required double y0 = 6 [(dccl.field) = { min: -10000 max: 10000 precision: 1 }];
  required double x1 = 7 [(dccl.field) = { min: -10000 max: 10000 precision: 1 }];
  required double y1 = 8 [(dccl.field) = { min: -10000 max: 10000 precision: 1 }];
  required double depth = 9 [(dccl.field) = { min: 0 max: 6000 precision: 1 }];
  required string label = 10 [(dccl.field) = { max_length: 12 }];
}
)";

std::string queue_type(const std::string& type) {
  return "  type { type: \"" + type + "\" policy { ttl_s: 600 }\n" +
         "         roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } }\n";
}

// Who hears whom on the acoustic side (see the header).
std::vector<int> acoustic_peers(int node) {
  switch (node) {
    case kBuoy: return {kVehicleA};
    case kVehicleA: return {kBuoy, kVehicleB};
    case kVehicleB: return {kVehicleA};
    default: return {};
  }
}

std::string routing(int node) {
  switch (node) {
    case kShore:
      return "routing { hop_limit: " + std::to_string(kShoreHopLimit) +
             "\n  route { dest_min: 3 dest_max: 4 next_hop: 2 link: \"iridium\" }\n"
             "  route { dest: 20 next_hop: 2 link: \"iridium\" } }\n";
    case kBuoy:
      return "routing { route { dest: 1 next_hop: 1 link: \"iridium\" }\n"
             "  route { dest: 20 next_hop: 3 link: \"acoustic\" } }\n";
    case kVehicleA:
      return "routing { route { dest: 1 next_hop: 2 link: \"acoustic\" }\n"
             "  route { dest: 20 next_hop: 2 link: \"acoustic\" } }\n";
    default:
      return "routing { route { dest: 1 next_hop: 3 link: \"acoustic\" } }\n";
  }
}

}  // namespace

GatewayFleet::GatewayFleet()
    : dir_(fs::path("/tmp") / ("acomms-gateway-fleet-" + std::to_string(::getpid()))),
      mo_port_(free_tcp_port()),
      directip_({.shore_mo_address = "127.0.0.1:" + std::to_string(mo_port_),
                 .mo_retry = 200ms,
                 .expect_mo_confirmation = true}),
      modem_(directip_, fake_iridium::FakeSbdConfig{.imei = kImei, .session_time = 300ms, .auto_ring = true}) {
  fs::remove_all(dir_);
  fs::create_directories(dir_);
  std::ofstream(dir_ / "survey_plan.proto") << kSurveyPlanProto;
  for (int node : {kBuoy, kVehicleA, kVehicleB}) sim_port_[node] = free_udp_port();
}

GatewayFleet::~GatewayFleet() {
  stop_all();
  if (!::testing::Test::HasFailure()) fs::remove_all(dir_);
}

std::string GatewayFleet::name(int node) {
  switch (node) {
    case kShore: return "shore";
    case kBuoy: return "buoy";
    case kVehicleA: return "vehicle_a";
    case kVehicleB: return "vehicle_b";
    default: return "node" + std::to_string(node);
  }
}

std::string GatewayFleet::socket(int node) const { return (dir_ / (name(node) + ".sock")).string(); }

std::string GatewayFleet::acoustic_link(int node) const {
  std::ostringstream out;
  out << "link { name: \"acoustic\" driver { name: \"sim\" modem_id: " << node << " sim { position { x: "
      << 40 * (node - kBuoy) << " } listen: \"127.0.0.1:" << sim_port_.at(node) << "\"";
  for (int peer : acoustic_peers(node)) out << " peers: \"127.0.0.1:" << sim_port_.at(peer) << "\"";
  out << " } }\n  mac { name: \"fixed\"";
  for (int slot : {kBuoy, kVehicleA, kVehicleB}) {
    out << " slot { src: " << slot << " rate: 5 seconds: " << kAcousticSlotS << " }";
  }
  out << " max_range_m: 100 } }\n";
  return out.str();
}

std::string GatewayFleet::config_text(int node) const {
  const bool buoy = node == kBuoy;
  std::string rest = "dccl { proto_files: \"" + kExampleProto + "\"" +
                     (buoy ? std::string() : " proto_files: \"" + survey_plan_proto() + "\"") + " }\n";
  if (node == kShore) {
    rest += "link { name: \"iridium\" driver { name: \"iridium_shore\" modem_id: 1 iridium_shore {\n"
            "  mo_listen: \"127.0.0.1:" + std::to_string(mo_port_) + "\" mt_gateway: \"" + directip_.mt_address() +
            "\"\n  modems { imei: \"" + kImei + "\" modem_id: 2 }\n"
            "  mo_confirmation: true mt_check_interval_s: 0.5 mt_retry_min_s: 1 mt_retry_max_s: 2 } }\n"
            "  mac { name: \"none\" } }\n";
  } else {
    rest += acoustic_link(node);
  }
  if (buoy) {
    rest += "link { name: \"iridium\" " +
            iridium_vehicle_driver(kBuoy, modem_.port(), kShore, kImei,
                                   "mailbox_check_s: 60 send_check_s: 1 session_timeout_s: 4 command_timeout_s: 2") +
            "  mac { name: \"none\" } }\n";
  } else {
    // The buoy queues nothing of its own: what it holds is in custody.
    rest += "queue {\n" + queue_type("example.Status") + queue_type("example.Command") +
            queue_type("fleet.SurveyPlan") + "}\n";
  }
  return DaemonConfig{.data_dir = dir_ / name(node), .unix_socket = socket(node), .proto_file = "", .grpc_extra = "",
                      .rest = rest + routing(node)}
      .text();
}

void GatewayFleet::start_all() {
  for (int node : {kShore, kBuoy, kVehicleA, kVehicleB}) {
    ASSERT_NO_FATAL_FAILURE(start(node));
  }
}

void GatewayFleet::start(int node) {
  const fs::path file = dir_ / (name(node) + ".conf");
  std::ofstream(file, std::ios::trunc) << config_text(node);  // the same every start
  const int n = ++starts_[node];
  daemons_[node] = std::make_unique<ChildProcess>(
      ACOMMSD_BINARY, std::vector<std::string>{"--config", file.string()},
      (dir_ / (name(node) + "-" + std::to_string(n))).string());
  ASSERT_TRUE(wait_serving(*daemons_[node], socket(node))) << name(node) << ":\n" << daemons_[node]->stderr_text();
}

void GatewayFleet::kill(int node) {
  ChildProcess& d = *daemons_.at(node);
  d.signal(SIGKILL);
  d.wait(10s);
  ASSERT_EQ(d.exit_signal(), SIGKILL) << name(node) << " did not die by SIGKILL";
}

std::string GatewayFleet::logs(int node) const {
  std::string out;
  auto it = starts_.find(node);
  for (int n = 1; it != starts_.end() && n <= it->second; ++n) {
    std::ifstream in(dir_ / (name(node) + "-" + std::to_string(n) + ".err"));
    out += std::string(std::istreambuf_iterator<char>(in), {});
  }
  return out;
}

std::string GatewayFleet::all_logs() const {
  std::string out;
  for (int node : {kShore, kBuoy, kVehicleA, kVehicleB}) out += "\n--- " + name(node) + ":\n" + logs(node);
  return out + "\n(logs and stores in " + dir_.string() + ")";
}

void GatewayFleet::stop_all() {
  for (auto& [node, d] : daemons_) {
    if (!d || !d->running()) continue;
    d->signal(SIGTERM);
    EXPECT_EQ(d->wait(15s), std::optional<int>(0)) << name(node) << ":\n" << d->stderr_text();
  }
}

}  // namespace acomms::testing
