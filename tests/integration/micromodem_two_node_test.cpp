// Two real acommsd processes, each on its own fake Micro-Modem (one
// fake_micromodem process, two modems in one water, 300 m apart, on TCP
// ports like serial-to-TCP gateways), with fixed TDMA: a Command submitted
// on the topside reaches the vehicle's subscriber with the modem's link
// figures, and the modem's own ACK clears the topside's queue. Once at
// rate 0 (FSK) and once at rate 5 (PSK). The fake and the drivers run 4x
// faster than real time (--time-scale, driver.micromodem.time_scale) to
// keep the test short; the MAC's slots are real seconds.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>

#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr double kTimeScale = 4;
constexpr double kSlotSeconds = 4;

class MicroModemTwoNode : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-mm-" + std::to_string(::getpid()) + "-" + std::to_string(GetParam()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fake_ = std::make_unique<ChildProcess>(
        FAKE_MICROMODEM_BINARY,
        std::vector<std::string>{"--transport", "tcp", "--modem", "1,mm2,300,0,0", "--modem", "2,mm2,0,0,0",
                                 "--time-scale", std::to_string(kTimeScale)},
        (dir_ / "fake").string());
    ASSERT_TRUE(wait_until([this] { return ports_known(); }, 10s)) << fake_->stdout_text() << fake_->stderr_text();
    for (int id : {1, 2}) write_config(id);
    for (int id : {1, 2}) start(id);
  }
  void TearDown() override {
    for (auto& [id, daemon] : daemons_) {
      if (!daemon || !daemon->running()) continue;
      daemon->signal(SIGTERM);
      EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << name(id) << ":\n" << daemon->stderr_text();
    }
    if (fake_) fake_->signal(SIGTERM);
    fs::remove_all(dir_);
  }

  // "modem 1 mm2 tcp 127.0.0.1:40001" for both modems.
  bool ports_known() {
    for (const std::string& line : lines_of(fake_->stdout_text())) {
      int id = 0;
      char address[64] = {};
      if (std::sscanf(line.c_str(), "modem %d mm2 tcp %63s", &id, address) == 2) address_[id] = address;
    }
    return address_.size() == 2;
  }

  static std::string name(int id) { return id == 1 ? "vehicle" : "topside"; }
  std::string socket(int id) const { return (dir_ / (name(id) + ".sock")).string(); }

  void write_config(int id) {
    int rate = GetParam();
    std::ofstream config(dir_ / (name(id) + ".conf"));
    config << "data_dir: \"" << (dir_ / name(id)).string() << "\"\n"
           << "grpc { unix_socket: \"" << socket(id) << "\" }\n"
           << "dccl { proto_files: \"" << ACOMMS_SOURCE_DIR << "/examples/messages.proto\" }\n"
           << "driver { name: \"micromodem\" modem_id: " << id << " micromodem { port: \"tcp:" << address_[id]
           << "\" time_scale: " << kTimeScale << " max_range_m: 1000 } }\n"
           << "mac { name: \"fixed\" slot { src: 1 rate: " << rate << " seconds: " << kSlotSeconds
           << " } slot { src: 2 rate: " << rate << " seconds: " << kSlotSeconds << " } }\n"
           << "queue {\n"
           << "  type { type: \"example.Command\" policy { value_base: 5 }\n"
           << "         roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } }\n"
           << "}\n";
  }

  void start(int id) {
    daemons_[id] = std::make_unique<ChildProcess>(
        ACOMMSD_BINARY, std::vector<std::string>{"--config", (dir_ / (name(id) + ".conf")).string()},
        (dir_ / name(id)).string() + "-log");
    ASSERT_TRUE(wait_serving(*daemons_[id], socket(id))) << daemons_[id]->stderr_text();
  }

  int queued(int id) {
    grpc::ClientContext context;
    v1::ListQueuedRequest request;
    request.set_type("example.Command");
    v1::ListQueuedResponse response;
    EXPECT_TRUE(api(socket(id))->ListQueued(&context, request, &response).ok());
    return response.messages_size();
  }

  v1::LinkStatusResponse link_status(int id) {
    grpc::ClientContext context;
    v1::LinkStatusResponse response;
    EXPECT_TRUE(api(socket(id))->LinkStatus(&context, v1::LinkStatusRequest(), &response).ok());
    return response;
  }

  fs::path dir_;
  std::unique_ptr<ChildProcess> fake_;
  std::map<int, std::string> address_;
  std::map<int, std::unique_ptr<ChildProcess>> daemons_;
};

TEST_P(MicroModemTwoNode, ACommandReachesTheVehicleWithLinkFiguresAndTheModemsAckClearsTheQueue) {
  auto stub = api(socket(1));
  grpc::ClientContext subscribe_context;
  v1::SubscribeRequest subscribe;
  subscribe.add_types("example.Command");
  auto reader = stub->Subscribe(&subscribe_context, subscribe);
  reader->WaitForInitialMetadata();
  std::mutex mutex;
  std::vector<v1::ReceivedMessage> received;
  std::thread reading([&] {
    v1::ReceivedMessage message;
    while (reader->Read(&message)) {
      std::lock_guard lock(mutex);
      received.push_back(message);
    }
  });

  grpc::ClientContext submit_context;
  v1::SubmitRequest request;
  request.set_type("example.Command");
  request.set_json(R"({"dest": 1, "kind": "GOTO", "x": 200, "y": -50, "depth": 30, "seq": 7})");
  v1::SubmitResponse response;
  ASSERT_TRUE(api(socket(2))->Submit(&submit_context, request, &response).ok());

  bool heard = wait_until(
      [&] {
        std::lock_guard lock(mutex);
        return !received.empty();
      },
      60s, 100ms);
  bool cleared = heard && wait_until([&] { return queued(2) == 0; }, 30s, 200ms);
  subscribe_context.TryCancel();
  reading.join();
  ASSERT_TRUE(heard) << "vehicle:\n" << daemons_[1]->stderr_text() << "\ntopside:\n" << daemons_[2]->stderr_text();
  const v1::ReceivedMessage& command = received.front();
  EXPECT_EQ(command.src(), 2);
  EXPECT_EQ(command.dest(), 1);
  EXPECT_EQ(command.link().transmission_src(), 2);
  EXPECT_EQ(command.link().rate(), GetParam());
  EXPECT_TRUE(command.link().has_snr_in_db());
  EXPECT_TRUE(command.link().has_signal_level_db());
  EXPECT_EQ(command.link().packet_type(), GetParam() == 0 ? 1 : 3);  // FSK, PSK
  EXPECT_TRUE(cleared) << "the modem's ACK did not clear the topside's queue:\n" << daemons_[2]->stderr_text();
  EXPECT_GE(link_status(1).counters().receptions_with_figures(), 1u);
  EXPECT_GE(link_status(2).counters().acks_received(), 1u);
  // The raw link log, through acommsctl: the vehicle's start-up set SRC 1.
  RunResult raw = run(ACOMMSCTL_BINARY, {"--socket", socket(1), "link", "raw", "--no-follow", "-n", "100000"},
                      (dir_ / "raw").string());
  EXPECT_EQ(raw.exit_code, 0) << raw.err;
  EXPECT_NE(raw.out.find(" >> $CCCFG,SRC,1*"), std::string::npos) << raw.out.substr(0, 2000);
  EXPECT_NE(raw.out.find(" << $CACFG,SRC,1*"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Rates, MicroModemTwoNode, ::testing::Values(0, 5),
                         [](const ::testing::TestParamInfo<int>& info) { return "Rate" + std::to_string(info.param); });

}  // namespace
}  // namespace acomms::testing
