// Vehicle to shore over Iridium, end to end (issue 29's "must be shown"):
// two real acommsd processes and both fakes of tests/fakes/iridium joined.
//
//   vehicle (modem 2)                                       shore (modem 1)
//   link "acoustic": sim driver, alone on its channel
//   link "iridium":  iridium driver -> fake 9603 (TCP, in this process)
//                       -> FakeDirectIpGateway  --MO push-->  iridium_shore
//                                               <--MT submit--
//
// The vehicle routes example.Status to the shore "acoustic, then iridium"
// with a short fallback_after_s: nobody answers on the acoustic channel, so
// the Statuses wait there for that silence and then go by satellite (not
// before). Commands the shore queues for modem 2 become MTs at the gateway;
// the fake rings and the vehicle fetches them. The fake modem's faults are
// switched on while the daemons run: a session that reaches the gateway but
// reports 13 to the modem (the resend carries the same MOMSN), a session
// whose answer is lost (the MOMSN says it went: no resend), an MT offered
// twice, a reboot in the middle of a session, and no network for a while.
// Every Status reaches the shore's subscriber once and every Command the
// vehicle's subscriber once. The gateway's side of each MO is recorded
// (RecordingGateway), so the test also shows what crossed the paid link.
//
// Real time, because the two daemons and the fake are separate processes
// and threads; the fake's sessions take 1 s and the intervals are short,
// so a test takes some 20-60 s. The fake's session transcript is printed.

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "child_process.h"
#include "daemon_harness.h"
#include "dccl/codec.h"
#include "fake_directip_gateway.h"
#include "iridium_vehicle_link.h"
#include "stream_subscriber.h"
#include "tcp_modem_host.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using fake_iridium::FakeDirectIpGateway;
using fake_iridium::FakeSbdConfig;
using fake_iridium::FakeSbdModem;
using fake_iridium::InMemorySbdGateway;
using fake_iridium::MtMessage;
using fake_iridium::SbdGateway;
using fake_iridium::TcpModemHost;

constexpr int kShore = 1;
constexpr int kVehicle = 2;
constexpr double kFallbackS = 6;
const std::string kImei = "300234010000001";
const std::string kProto = std::string(ACOMMS_SOURCE_DIR) + "/examples/messages.proto";

// The fake DirectIP gateway behind the fake modem, with every MO the modem
// delivered kept in memory as well (what was paid for).
class RecordingGateway : public SbdGateway {
 public:
  explicit RecordingGateway(FakeDirectIpGateway& directip) : directip_(directip) {}
  void mo_received(const std::string& imei, uint16_t momsn, const std::string& payload) override {
    record_.mo_received(imei, momsn, payload);
    directip_.mo_received(imei, momsn, payload);
  }
  std::optional<MtMessage> take_mt(const std::string& imei) override { return directip_.take_mt(imei); }
  int mt_queued(const std::string& imei) const override { return directip_.mt_queued(imei); }
  std::vector<InMemorySbdGateway::Mo> mo() const { return record_.mo(); }

 private:
  FakeDirectIpGateway& directip_;
  InMemorySbdGateway record_;
};

std::string queue_type(const std::string& type, const std::string& extra = "") {
  return "  type { type: \"" + type + "\" policy { ttl_s: 600 }\n" +
         "         roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" }" + extra +
         " }\n";
}

// seq -> how many times it was received.
std::map<int, int> seq_counts(const std::vector<v1::ReceivedMessage>& received) {
  static const std::regex seq(R"("seq":\s*(\d+))");
  std::map<int, int> counts;
  for (const auto& message : received) {
    std::smatch match;
    const std::string json = message.json();
    if (std::regex_search(json, match, seq)) ++counts[std::stoi(match[1])];
  }
  return counts;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class IridiumEndToEnd : public ::testing::Test {
 protected:
  IridiumEndToEnd()
      : dir_(fs::path("/tmp") / ("acomms-iridium-e2e-" + std::to_string(::getpid()))),
        mo_port_(free_tcp_port()),
        directip_({.shore_mo_address = "127.0.0.1:" + std::to_string(mo_port_),
                   .mo_retry = 200ms,
                   .expect_mo_confirmation = true}),
        gateway_(directip_),
        host_(gateway_, FakeSbdConfig{.imei = kImei, .session_time = 1s, .auto_ring = true}) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    codec_.load(kProto);
  }
  ~IridiumEndToEnd() override {
    for (ChildProcess* daemon : {vehicle_.get(), shore_.get()}) {
      if (daemon == nullptr || !daemon->running()) continue;
      daemon->signal(SIGTERM);
      EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << daemon->stderr_text();
    }
    if (!HasFailure()) fs::remove_all(dir_);
  }

  std::string socket(const std::string& node) const { return (dir_ / (node + ".sock")).string(); }

  // Writes NODE.conf (the common head, then `rest`), starts NODE's acommsd
  // and waits until it serves.
  void start(const std::string& node, const std::string& rest, std::unique_ptr<ChildProcess>& daemon) {
    const fs::path file = dir_ / (node + ".conf");
    DaemonConfig{
        .data_dir = dir_ / node, .unix_socket = socket(node), .proto_file = kProto, .grpc_extra = "", .rest = rest}
        .write(file);
    daemon = std::make_unique<ChildProcess>(ACOMMSD_BINARY, std::vector<std::string>{"--config", file.string()},
                                            (dir_ / (node + "-log")).string());
    ASSERT_TRUE(wait_serving(*daemon, socket(node))) << daemon->stderr_text();
  }
  void start_shore() {
    start("shore",
          "driver { name: \"iridium_shore\" modem_id: 1 iridium_shore {\n"
          "  mo_listen: \"127.0.0.1:" + std::to_string(mo_port_) + "\" mt_gateway: \"" + directip_.mt_address() + "\"\n"
          "  modems { imei: \"" + kImei + "\" modem_id: 2 }\n"
          "  mo_confirmation: true mt_check_interval_s: 0.5 mt_retry_min_s: 1 mt_retry_max_s: 2 } }\n"
          "mac { name: \"none\" }\n"
          "queue {\n" + queue_type("example.Status") + queue_type("example.Command") + "}\n",
          shore_);
  }
  // The vehicle: the acoustic link first (nobody else on its channel), the
  // satellite second; Status to the shore routed acoustic, then iridium.
  void start_vehicle() {
    std::ostringstream route;
    route << "\n         route { dest: " << kShore << " link: \"acoustic\" link: \"iridium\" fallback_after_s: "
          << kFallbackS << " }";
    launched_ = std::chrono::steady_clock::now();
    start("vehicle",
          "link { name: \"acoustic\" driver { name: \"sim\" modem_id: 2 }\n"
          "  mac { name: \"fixed\" slot { src: 2 rate: 5 seconds: 2 } max_range_m: 400 } }\n"
          "link { name: \"iridium\" " +
              iridium_vehicle_driver(kVehicle, host_.port(), kShore, kImei,
                                     "mailbox_check_s: 60 send_check_s: 1 session_timeout_s: 4 command_timeout_s: 2") +
              "  mac { name: \"none\" } }\n"
              "queue {\n" + queue_type("example.Status", route.str()) + queue_type("example.Command") + "}\n",
          vehicle_);
  }

  static void submit(const std::string& socket, const std::string& type, const std::string& json) {
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type(type);
    request.set_json(json);
    v1::SubmitResponse response;
    grpc::Status status = api(socket)->Submit(&context, request, &response);
    ASSERT_TRUE(status.ok()) << status.error_message();
  }
  void status(int seq) {
    submit(socket("vehicle"), "example.Status",
           R"({"src": 2, "dest": 1, "x": 120, "y": -40, "depth": 0, "time": )" + std::to_string(std::time(nullptr)) +
               R"(, "seq": )" + std::to_string(seq) + "}");
  }
  void command(int seq) {
    submit(socket("shore"), "example.Command",
           R"({"src": 1, "dest": 2, "kind": "HOLD", "time": )" + std::to_string(std::time(nullptr)) +
               R"(, "seq": )" + std::to_string(seq) + "}");
  }
  int queued(const std::string& node, const std::string& type) {
    grpc::ClientContext context;
    v1::ListQueuedRequest request;
    request.set_type(type);
    v1::ListQueuedResponse response;
    EXPECT_TRUE(api(socket(node))->ListQueued(&context, request, &response).ok());
    return response.messages_size();
  }
  // Waits until the fake has said nothing for 1.5 s (no session running):
  // a fault switched on next hits the session the test causes.
  void wait_quiet() {
    size_t length = host_.transcript().size();
    auto since = std::chrono::steady_clock::now();
    ASSERT_TRUE(wait_until(
        [&] {
          size_t now = host_.transcript().size();
          if (now != length) length = now, since = std::chrono::steady_clock::now();
          return std::chrono::steady_clock::now() - since > 1500ms;
        },
        30s, 100ms));
  }
  std::string vehicle_modem_line() {
    grpc::ClientContext context;
    v1::LinkStatusRequest request;
    request.set_link("iridium");
    v1::LinkStatusResponse response;
    EXPECT_TRUE(api(socket("vehicle"))->LinkStatus(&context, request, &response).ok());
    return response.driver().modem();
  }
  // Runs `work` on the fake modem's thread.
  void modem(const std::function<void(FakeSbdModem&)>& work) { host_.call(work); }

  std::string logs() {
    return "\n--- vehicle:\n" + (vehicle_ ? vehicle_->stderr_text() : "") + "\n--- shore:\n" +
           (shore_ ? shore_->stderr_text() : "") + "\n--- fake 9603:\n" + host_.transcript();
  }
  // The seqs inside one MO or MT payload.
  std::set<int> seqs_in(const std::string& payload) {
    std::set<int> seqs;
    for (const auto& message : codec_.decode(payload)) {
      const auto* field = message->GetDescriptor()->FindFieldByName("seq");
      seqs.insert(static_cast<int>(message->GetReflection()->GetUInt32(*message, field)));
    }
    return seqs;
  }

  // Both daemons, a subscriber on each (Statuses at the shore, Commands at
  // the vehicle), and Status 1 / Command 20 across: after this the vehicle
  // has fallen back to the satellite.
  void start_and_cross_first() {
    ASSERT_NO_FATAL_FAILURE(start_shore());
    shore_statuses_ = std::make_unique<StreamSubscriber>(socket("shore"), "example.Status");
    ASSERT_NO_FATAL_FAILURE(start_vehicle());
    vehicle_commands_ = std::make_unique<StreamSubscriber>(socket("vehicle"), "example.Command");
    status(1);
    command(20);
    ASSERT_TRUE(shore_has(1)) << logs();
    ASSERT_TRUE(vehicle_has(20)) << logs();
  }
  bool shore_has(int seq) {
    return shore_statuses_->wait_for([seq](const auto& r) { return seq_counts(r).count(seq) > 0; }, 60s);
  }
  bool vehicle_has(int seq) {
    return vehicle_commands_->wait_for([seq](const auto& r) { return seq_counts(r).count(seq) > 0; }, 60s);
  }

  // Once both queues are empty (and after room for a wrong resend): each
  // Status reached the shore's subscriber once and each Command the
  // vehicle's; each Status crossed the gateway `mo_copies` times, always
  // under one MOMSN (a resend under a new MOMSN is a session paid twice:
  // the MOMSN rule says it is not needed), and each Command in one MT.
  void expect_each_once(const std::map<int, int>& statuses, const std::map<int, int>& commands,
                        const std::map<int, int>& mo_copies) {
    ASSERT_TRUE(wait_until(
        [&] { return queued("vehicle", "example.Status") == 0 && queued("shore", "example.Command") == 0; }, 60s))
        << logs();
    std::this_thread::sleep_for(2s);
    EXPECT_EQ(seq_counts(shore_statuses_->received()), statuses)
        << logs();
    EXPECT_EQ(seq_counts(vehicle_commands_->received()), commands)
        << logs();
    for (const auto& message : shore_statuses_->received()) EXPECT_EQ(message.src(), kVehicle);
    for (const auto& message : vehicle_commands_->received()) EXPECT_EQ(message.src(), kShore);

    std::map<int, std::set<uint16_t>> momsns;
    std::map<int, int> copies;
    for (const auto& mo : gateway_.mo()) {
      for (int seq : seqs_in(mo.payload)) momsns[seq].insert(mo.momsn), ++copies[seq];
    }
    EXPECT_EQ(copies, mo_copies) << logs();
    for (const auto& [seq, numbers] : momsns) {
      EXPECT_EQ(numbers.size(), 1u) << "Status " << seq << " went in " << numbers.size() << " MOMSNs" << logs();
    }
    std::map<int, int> in_mts;
    for (const auto& mt : directip_.mt_submissions()) {
      for (int seq : seqs_in(mt.payload)) ++in_mts[seq];
    }
    EXPECT_EQ(in_mts, commands);
  }

  // Prints the fake's transcript around each fault, for the record.
  void print_transcript_excerpt() {
    const std::vector<std::string> all = lines_of(host_.transcript());
    std::cout << "fake 9603 session transcript around each fault (" << all.size() << " lines in all):\n";
    size_t shown_to = 0;
    for (size_t i = 0; i < all.size(); ++i) {
      if (all[i].find("(fault:") == std::string::npos && all[i].find("(network back)") == std::string::npos) continue;
      const size_t from = std::max(shown_to, i >= 3 ? i - 3 : 0), to = std::min(all.size(), i + 5);
      if (from > shown_to) std::cout << "  ...\n";
      for (size_t j = from; j < to; ++j) std::cout << "  " << all[j] << "\n";
      shown_to = to;
    }
  }
  std::string summary() {
    const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - launched_).count();
    std::ostringstream out;
    out << took_s << " s from the vehicle's launch: " << gateway_.mo().size() << " MO(s) at the gateway, "
        << directip_.mt_submissions().size() << " MT(s) submitted; the shore's subscriber got "
        << shore_statuses_->received().size() << " Status(es), the vehicle's " << vehicle_commands_->received().size()
        << " Command(s)";
    return out.str();
  }

  fs::path dir_;
  int mo_port_;
  FakeDirectIpGateway directip_;
  RecordingGateway gateway_;
  TcpModemHost host_;
  dccl::Codec codec_;
  std::unique_ptr<ChildProcess> shore_, vehicle_;
  std::unique_ptr<StreamSubscriber> shore_statuses_, vehicle_commands_;
  std::chrono::steady_clock::time_point launched_;
};

TEST_F(IridiumEndToEnd, StatusFallsBackToIridiumAfterTheSilenceAndCommandsReachTheVehicleOnce) {
  ASSERT_NO_FATAL_FAILURE(start_shore());
  shore_statuses_ = std::make_unique<StreamSubscriber>(socket("shore"), "example.Status");
  ASSERT_NO_FATAL_FAILURE(start_vehicle());
  vehicle_commands_ = std::make_unique<StreamSubscriber>(socket("vehicle"), "example.Command");
  status(1);

  // Not before the silence: until fallback_after_s has passed since the
  // vehicle started, nothing reaches the gateway and the Status stays queued.
  auto since_launch = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - launched_).count();
  };
  while (since_launch() < kFallbackS - 0.5) {
    ASSERT_TRUE(gateway_.mo().empty()) << "an MO at " << since_launch() << " s, before the fallback" << logs();
    std::this_thread::sleep_for(100ms);
  }
  EXPECT_EQ(queued("vehicle", "example.Status"), 1) << logs();
  // After it: by satellite.
  ASSERT_TRUE(wait_until([&] { return !gateway_.mo().empty(); }, 30s)) << logs();
  const double fell_back_s = since_launch();
  EXPECT_GE(fell_back_s, kFallbackS);
  ASSERT_TRUE(shore_has(1)) << logs();

  // More Statuses (now on the satellite), and Commands from the shore: one
  // by `acommsctl send`, two by the API.
  for (int seq : {2, 3, 4}) status(seq);
  RunResult sent = run(ACOMMSCTL_BINARY,
                       {"--socket", socket("shore"), "send", "example.Command", "src=1", "dest=2",
                        "time=" + std::to_string(std::time(nullptr)), "kind=HOLD", "seq=42"},
                       (dir_ / "ctl").string());
  ASSERT_EQ(sent.exit_code, 0) << sent.err;
  command(43);
  command(44);
  for (int seq : {2, 3, 4}) ASSERT_TRUE(shore_has(seq)) << logs();
  for (int seq : {42, 43, 44}) ASSERT_TRUE(vehicle_has(seq)) << logs();
  expect_each_once({{1, 1}, {2, 1}, {3, 1}, {4, 1}}, {{42, 1}, {43, 1}, {44, 1}},
                   {{1, 1}, {2, 1}, {3, 1}, {4, 1}});
  std::cout << "fell back to iridium " << fell_back_s << " s after the vehicle's launch (fallback_after_s "
            << kFallbackS << "); " << summary() << "\n";
}

// Fault 1, the gateway has the MO but the modem is told 13: the retry
// brings the same MO (same MOMSN) to the gateway again, and the shore's
// (IMEI, MOMSN, payload) dedup hands it up once; that retry's session also
// offers the last MT again, which the vehicle's MTMSN window drops.
// Fault 2, a session whose answer is lost: the MOMSN says it went, so it
// is acknowledged and not sent again.
TEST_F(IridiumEndToEnd, FailureAfterTheGatewayAndALostAnswerDeliverNothingTwice) {
  ASSERT_NO_FATAL_FAILURE(start_and_cross_first());

  ASSERT_NO_FATAL_FAILURE(wait_quiet());
  const size_t before = gateway_.mo().size();
  modem([](FakeSbdModem& m) {
    m.fail_at_gateway(1);
    m.repeat_mts(1);
  });
  status(10);
  ASSERT_TRUE(wait_until([&] { return gateway_.mo().size() >= before + 2; }, 60s)) << logs();
  ASSERT_TRUE(shore_has(10)) << logs();
  auto mo = gateway_.mo();
  EXPECT_EQ(mo[before].momsn, mo[before + 1].momsn);
  EXPECT_EQ(mo[before].payload, mo[before + 1].payload);

  ASSERT_TRUE(wait_until([&] { return queued("vehicle", "example.Status") == 0; }, 30s)) << logs();
  ASSERT_NO_FATAL_FAILURE(wait_quiet());
  modem([](FakeSbdModem& m) { m.lose_answers(1); });
  status(11);
  ASSERT_TRUE(shore_has(11)) << logs();
  EXPECT_NE(host_.transcript().find("its answer is lost"), std::string::npos) << logs();

  expect_each_once({{1, 1}, {10, 1}, {11, 1}}, {{20, 1}}, {{1, 1}, {10, 2}, {11, 1}});
  // The layers that removed the copies, by their logs: the shore's MO
  // dedup (not only the queues' duplicate window) and the MTMSN window.
  EXPECT_EQ(count_of(shore_->stderr_text(), "was handed up before: dropped"), 1u) << logs();
  EXPECT_EQ(count_of(vehicle_->stderr_text(), "(MTMSN and payload already delivered): dropped"), 1u) << logs();
  print_transcript_excerpt();
  std::cout << summary() << "\n";
}

// Fault 3, a reboot in the middle of a session, with a Status and a Command
// waiting (the session never happened: both are sent afterwards). Fault 4,
// no network for a while: the driver sees the service go (+CIEV, or a
// session failing with 32) and nothing crosses until it is back.
TEST_F(IridiumEndToEnd, RebootMidSessionAndNoNetworkLoseNothing) {
  ASSERT_NO_FATAL_FAILURE(start_and_cross_first());

  ASSERT_NO_FATAL_FAILURE(wait_quiet());
  size_t sessions_before = 0;
  modem([&](FakeSbdModem& m) { sessions_before = m.session_commands().size(); });
  status(12);
  command(21);
  bool rebooted = false;
  ASSERT_TRUE(wait_until(
      [&] {
        modem([&](FakeSbdModem& m) {
          if (m.session_commands().size() > sessions_before) m.reboot(2s), rebooted = true;
        });
        return rebooted;
      },
      30s, 10ms))
      << logs();
  ASSERT_TRUE(shore_has(12)) << logs();
  ASSERT_TRUE(vehicle_has(21)) << logs();

  modem([](FakeSbdModem& m) { m.set_network(false); });
  status(13);
  command(22);
  ASSERT_TRUE(wait_until([&] { return vehicle_modem_line().find("no service") != std::string::npos; }, 30s))
      << logs();
  std::this_thread::sleep_for(3s);
  EXPECT_EQ(seq_counts(shore_statuses_->received()).count(13), 0u) << "delivered without a network?" << logs();
  EXPECT_EQ(seq_counts(vehicle_commands_->received()).count(22), 0u) << "delivered without a network?" << logs();
  modem([](FakeSbdModem& m) { m.set_network(true); });
  ASSERT_TRUE(shore_has(13)) << logs();
  ASSERT_TRUE(vehicle_has(22)) << logs();

  expect_each_once({{1, 1}, {12, 1}, {13, 1}}, {{20, 1}, {21, 1}, {22, 1}}, {{1, 1}, {12, 1}, {13, 1}});
  print_transcript_excerpt();
  std::cout << summary() << "\n";
}

}  // namespace
}  // namespace acomms::testing
