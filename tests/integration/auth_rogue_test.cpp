// Nobody commands a vehicle they should not, with real daemons on the
// loopback sim channel: the vehicle (1) and the topside (2) share the fleet
// key and example.Command is authenticated; a rogue node (3, its own
// acommsd) has the wrong key, then none. The rogue's radio also does what a
// daemon will not: the test listens as one more peer of the topside,
// records its real frames, and sends copies (bit-flipped, as they were, or
// as they were but under the rogue's own id) to the vehicle's modem from
// the rogue's position, again after the vehicle was SIGKILLed and
// restarted.
//
// Shown: no forged, altered or replayed Command reaches the vehicle's
// subscribers or event log; each is counted under its reason in
// LinkStatus; the real Commands arrive exactly once. Real time (the
// daemons' clocks), because the kill and restart need real processes; a
// replay minutes later (and minutes later after the receiver's restart),
// the window's stale rule and the key roll-over are shown on the simulated
// clock (tests/unit/queue/auth_guard_test.cpp, auth_resend_test.cpp), so
// that this test stays short.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "daemon_config.h"
#include "daemon_harness.h"
#include "sim/sim_envelope.h"
#include "stream_subscriber.h"
#include "wait_until.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr double kSlotSeconds = 3;
constexpr char kCommandId = 21 << 1;  // example.Command's DCCL id byte
const std::map<int, std::string> kNames = {{1, "vehicle"}, {2, "topside"}, {3, "rogue"}};

// A UDP socket on 127.0.0.1 that keeps every sim envelope sent to it, and
// sends envelopes of its own: the rogue's radio.
class RogueRadio {
 public:
  RogueRadio() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in at{};
    at.sin_family = AF_INET;
    at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&at), sizeof at);
    socklen_t length = sizeof at;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&at), &length);
    port_ = ntohs(at.sin_port);
    timeval wake{0, 200'000};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &wake, sizeof wake);
    thread_ = std::thread([this] {
      char buffer[65536];
      while (running_) {
        ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
        if (n <= 0) continue;
        std::string error;
        if (auto envelope = drivers::decode_envelope(std::string_view(buffer, n), &error)) {
          std::lock_guard lock(mutex_);
          heard_.push_back(*envelope);
        }
      }
    });
  }
  ~RogueRadio() {
    running_ = false;
    thread_.join();
    ::close(fd_);
  }
  int port() const { return port_; }

  // The first DATA transmission heard whose frame starts with a Command.
  std::optional<drivers::SimEnvelope> recorded_command() {
    std::lock_guard lock(mutex_);
    for (const auto& envelope : heard_) {
      const auto& t = envelope.transmission;
      if (t.type() == v1::ModemTransmission::DATA && t.frame_size() > 0 && !t.frame(0).empty() &&
          t.frame(0)[0] == kCommandId) {
        return envelope;
      }
    }
    return std::nullopt;
  }

  // Sends `envelope` from the rogue's modem (node 3, x = 150 m), starting
  // now, to `port`. Short (10 ms), so that it seldom overlaps the nodes'
  // own packets: the channel is busy with one every slot. The packet is
  // replayed whole, its source included, unless `as_src` gives another.
  void send(drivers::SimEnvelope envelope, int port, std::optional<int32_t> as_src = std::nullopt) {
    if (as_src) envelope.transmission.set_src(*as_src);
    // The sim's envelope names the transmitting modem (a real receiver
    // knows only the header): the id the packet claims, from the rogue's
    // position.
    envelope.sender = envelope.transmission.src();
    envelope.duration = std::chrono::milliseconds(10);
    envelope.position = {150, 0, 0};
    envelope.start = core::Clock::time_point(std::chrono::duration_cast<core::Clock::time_point::duration>(
        std::chrono::system_clock::now().time_since_epoch()));
    const std::string bytes = drivers::encode(envelope);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    to.sin_port = htons(static_cast<uint16_t>(port));
    ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  }

 private:
  int fd_ = -1;
  int port_ = 0;
  std::atomic<bool> running_{true};
  std::mutex mutex_;
  std::vector<drivers::SimEnvelope> heard_;
  std::thread thread_;
};

class AuthRogueTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-auth-rogue-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    for (int id : {1, 2, 3}) port_[id] = free_udp_port();
    keyring("fleet.keyring", "key 1 000102030405060708090a0b0c0d0e0f\nsign 1\n");
    keyring("rogue.keyring", "key 1 f0e0d0c0b0a090807060504030201000\nsign 1\n");
  }
  void TearDown() override {
    for (auto& [id, daemon] : daemons_) {
      if (!daemon || !daemon->running()) continue;
      daemon->signal(SIGTERM);
      EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << kNames.at(id) << ":\n" << daemon->stderr_text();
    }
    if (!HasFailure()) fs::remove_all(dir_);
  }

  void keyring(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    fs::permissions(dir_ / name, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
  }

  // `keyring_file` empty: no auth section (a rogue without a key).
  void write_config(int id, const std::string& keyring_file, const std::string& peers) {
    const std::string auth =
        keyring_file.empty()
            ? ""
            : "auth { keyring_file: \"" + (dir_ / keyring_file).string() +
                  "\" tag_bits: 64 type { type: \"example.Command\" window_s: 600 } }\n";
    // The rogue sends each forged Command once (no ACK to wait for).
    const std::string command_policy = id == 3 ? "ack: false ttl_s: 300" : "ttl_s: 300";
    DaemonConfig config{.data_dir = dir_ / kNames.at(id),
                        .unix_socket = socket(id),
                        .proto_file = std::string(ACOMMS_SOURCE_DIR) + "/examples/messages.proto"};
    std::string slots;
    for (int src : {1, 2, 3}) slots += "slot { src: " + std::to_string(src) + " rate: 5 seconds: " + std::to_string(kSlotSeconds) + " } ";
    config.rest = "driver { name: \"sim\" modem_id: " + std::to_string(id) + " sim { position { x: " +
                  std::to_string(id == 1 ? 300 : id == 2 ? 0 : 150) + " } listen: \"127.0.0.1:" +
                  std::to_string(port_[id]) + "\" " + peers + " } }\n" + "mac { name: \"fixed\" " + slots +
                  "max_range_m: 400 }\n" + "queue { type { type: \"example.Command\" policy { " + command_policy +
                  " } roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } } }\n" +
                  auth;
    config.write(dir_ / (kNames.at(id) + ".conf"));
  }
  std::string peer(int port) { return "peers: \"127.0.0.1:" + std::to_string(port) + "\" "; }

  void start(int id) {
    daemons_[id] = std::make_unique<ChildProcess>(
        ACOMMSD_BINARY, std::vector<std::string>{"--config", (dir_ / (kNames.at(id) + ".conf")).string()},
        (dir_ / (kNames.at(id) + "-" + std::to_string(++starts_))).string());
    ASSERT_TRUE(wait_serving(*daemons_[id], socket(id))) << daemons_[id]->stderr_text();
  }
  std::string socket(int id) const { return (dir_ / (kNames.at(id) + ".sock")).string(); }

  int64_t submit_command(int id, int seq) {
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type("example.Command");
    request.set_json(R"({"dest": 1, "kind": "SURFACE", "seq": )" + std::to_string(seq) + "}");
    v1::SubmitResponse response;
    grpc::Status status = api(socket(id))->Submit(&context, request, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return response.message_id();
  }

  // The rogue's daemon sends a forged Command once (ack: false), and that
  // one packet can be lost to half-duplex when the vehicle's ACK of an
  // injected frame is on the air (seen once in CI): forge another, with a
  // new seq, until the vehicle counts one under auth_failed. None of them
  // may ever be delivered (the seqs received are checked at the end).
  bool forge_until_refused(int first_seq) {
    const uint64_t before = counters(1).auth_failed();
    for (int attempt = 0; attempt < 4; ++attempt) {
      if (submit_command(3, first_seq + 10 * attempt) <= 0) return false;
      if (wait_until([&] { return counters(1).auth_failed() > before; }, 20s, 200ms)) return true;
    }
    return false;
  }

  // What ListTypes says the trailer costs each message of example.Command.
  uint32_t trailer_bits(int id) {
    grpc::ClientContext context;
    v1::ListTypesRequest request;
    request.add_types("example.Command");
    v1::ListTypesResponse response;
    EXPECT_TRUE(api(socket(id))->ListTypes(&context, request, &response).ok());
    return response.types_size() == 1 ? response.types(0).auth_trailer_bits() : 9999;
  }

  v1::LinkCounters counters(int id) {
    grpc::ClientContext context;
    v1::LinkStatusResponse response;
    EXPECT_TRUE(api(socket(id))->LinkStatus(&context, v1::LinkStatusRequest(), &response).ok());
    return response.counters();
  }

  // Commands the vehicle's event log says it received (and so published).
  int commands_received() {
    grpc::ClientContext context;
    v1::EventsRequest request;
    request.add_kinds("received");
    request.add_types("example.Command");
    v1::EventsResponse response;
    EXPECT_TRUE(api(socket(1))->Events(&context, request, &response).ok());
    return response.events_size();
  }

  // The rogue's radio sends `envelope` to the vehicle until `counted` (of
  // the vehicle's counters) went up by one: a copy can be lost to a
  // collision or to the vehicle's own transmission (half duplex).
  bool inject_until_counted(drivers::SimEnvelope envelope, const std::function<uint64_t(const v1::LinkCounters&)>& counted,
                            std::optional<int32_t> as_src = std::nullopt) {
    const uint64_t before = counted(counters(1));
    for (int attempt = 0; attempt < 5; ++attempt) {
      radio_.send(envelope, port_[1], as_src);
      if (wait_until([&] { return counted(counters(1)) > before; }, 8s, 100ms)) {
        return counted(counters(1)) == before + 1;
      }
    }
    return false;
  }

  fs::path dir_;
  std::map<int, int> port_;
  std::map<int, std::unique_ptr<ChildProcess>> daemons_;
  int starts_ = 0;
  RogueRadio radio_;
};

std::vector<int> seqs(const std::vector<v1::ReceivedMessage>& received) {
  std::vector<int> out;
  for (const auto& m : received) {
    auto at = m.json().find("\"seq\":");
    out.push_back(at == std::string::npos ? -1 : std::stoi(m.json().substr(at + 6)));
  }
  return out;
}

auto auth_failed = [](const v1::LinkCounters& c) { return c.auth_failed(); };
auto replayed = [](const v1::LinkCounters& c) { return c.auth_replayed(); };

TEST_F(AuthRogueTest, ForgedFlippedAndReplayedCommandsAreRefusedAndRealOnesArriveOnce) {
  write_config(1, "fleet.keyring", peer(port_[2]) + peer(port_[3]));
  write_config(2, "fleet.keyring", peer(port_[1]) + peer(port_[3]) + peer(radio_.port()));
  write_config(3, "rogue.keyring", peer(port_[1]) + peer(port_[2]));
  start(1);
  start(2);
  start(3);
  EXPECT_EQ(trailer_bits(1), 48u + 64u) << "key id, time, counter and a 64-bit tag";

  // A real Command arrives.
  auto vehicle = std::make_unique<StreamSubscriber>(socket(1), "example.Command");
  ASSERT_GT(submit_command(2, 1), 0);
  ASSERT_TRUE(vehicle->wait_for([](const auto& got) { return !got.empty(); }, 30s)) << daemons_[1]->stderr_text();
  ASSERT_TRUE(wait_until([&] { return radio_.recorded_command().has_value(); }, 10s, 100ms));
  const drivers::SimEnvelope recorded = *radio_.recorded_command();

  // Forged with the wrong key, by the rogue's own daemon.
  ASSERT_TRUE(forge_until_refused(66)) << daemons_[1]->stderr_text();

  // Bit-flipped copies of the real frame: in the body, and in the tag.
  for (size_t byte : {size_t{2}, recorded.transmission.frame(0).size() - 1}) {
    drivers::SimEnvelope flipped = recorded;
    std::string& frame = *flipped.transmission.mutable_frame(0);
    frame[byte] = static_cast<char>(frame[byte] ^ 0x04);
    EXPECT_TRUE(inject_until_counted(flipped, auth_failed)) << "byte " << byte << "\n" << daemons_[1]->stderr_text();
  }
  // The real frame, replayed as it was (the topside's id in its header).
  EXPECT_TRUE(inject_until_counted(recorded, replayed)) << daemons_[1]->stderr_text();
  // And under the rogue's own id: the tag covers the sender, so it does not
  // pass for a new message from node 3.
  EXPECT_TRUE(inject_until_counted(recorded, auth_failed, 3)) << daemons_[1]->stderr_text();

  EXPECT_EQ(seqs(vehicle->received()), std::vector<int>{1});

  // The vehicle dies without warning and comes back: the replay is still one.
  daemons_[1]->signal(SIGKILL);
  daemons_[1]->wait(10s);
  vehicle.reset();
  start(1);
  auto restarted = std::make_unique<StreamSubscriber>(socket(1), "example.Command");
  EXPECT_TRUE(inject_until_counted(recorded, replayed)) << daemons_[1]->stderr_text();

  // The rogue without any key: a plain DCCL Command, no trailer.
  daemons_[3]->signal(SIGTERM);
  ASSERT_EQ(daemons_[3]->wait(15s), std::optional<int>(0));
  write_config(3, "", peer(port_[1]) + peer(port_[2]));
  start(3);
  EXPECT_EQ(trailer_bits(3), 0u) << "not authenticated there";
  EXPECT_TRUE(forge_until_refused(67)) << daemons_[1]->stderr_text();

  // A second real Command still arrives, once.
  ASSERT_GT(submit_command(2, 2), 0);
  ASSERT_TRUE(restarted->wait_for([](const auto& got) { return !got.empty(); }, 30s)) << daemons_[1]->stderr_text();
  // Wait for the topside's queue to empty (the ACK came): no resend can
  // still be on its way.
  ASSERT_TRUE(wait_until(
      [&] {
        grpc::ClientContext context;
        v1::ListQueuedRequest request;
        request.set_type("example.Command");
        v1::ListQueuedResponse response;
        return api(socket(2))->ListQueued(&context, request, &response).ok() && response.messages_size() == 0;
      },
      30s, 200ms));

  EXPECT_EQ(seqs(restarted->received()), std::vector<int>{2});
  EXPECT_EQ(commands_received(), 2) << "only the two real Commands are in the vehicle's event log";
  const v1::LinkCounters after = counters(1);
  EXPECT_EQ(after.auth_replayed(), 1u) << "the counters start again at the restart: the replay after it";
  EXPECT_GE(after.auth_failed(), 1u);
  EXPECT_EQ(after.auth_stale(), 0u);
}


// A fleet rolls from key 1 to key 2 without a restart: the vehicle's keyring
// gains key 2 with key 1 accepted until a time a few seconds ahead, the
// topside moves to signing with key 2, each re-read on SIGHUP; a node still
// signing with key 1 (the "rogue" daemon here, given the old key) is heard
// during the overlap and refused after it. Real time: `until` is a wall-clock
// time, and SIGHUP needs real processes.
TEST_F(AuthRogueTest, KeyRollAcceptsBothKeysDuringTheOverlapAndOnlyTheNewAfter) {
  const std::string key1 = "key 1 000102030405060708090a0b0c0d0e0f";
  const std::string key2 = "key 2 00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff";
  keyring("vehicle.keyring", key1 + "\nsign 1\n");
  keyring("topside.keyring", key1 + "\nsign 1\n");
  keyring("late.keyring", key1 + "\nsign 1\n");
  write_config(1, "vehicle.keyring", peer(port_[2]) + peer(port_[3]));
  write_config(2, "topside.keyring", peer(port_[1]) + peer(port_[3]));
  write_config(3, "late.keyring", peer(port_[1]) + peer(port_[2]));
  start(1);
  start(2);
  start(3);
  StreamSubscriber vehicle(socket(1), "example.Command");

  // Key 1 is accepted until 25 s from now.
  const std::time_t until = std::time(nullptr) + 25;
  char when[32];
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&until));
  keyring("vehicle.keyring", key1 + " until " + when + "\n" + key2 + "\nsign 1\n");
  daemons_[1]->signal(SIGHUP);
  ASSERT_TRUE(wait_until([&] { return daemons_[1]->stderr_text().find("auth: keyring reloaded: keys 1, 2") !=
                                      std::string::npos; }, 10s, 100ms))
      << daemons_[1]->stderr_text();
  keyring("topside.keyring", key2 + "\nsign 2\n");
  daemons_[2]->signal(SIGHUP);
  ASSERT_TRUE(wait_until([&] { return daemons_[2]->stderr_text().find("signing with 2") != std::string::npos; },
                         10s, 100ms));

  // The overlap: key 2 (topside) and key 1 (the late node) both arrive.
  ASSERT_GT(submit_command(2, 1), 0);
  ASSERT_GT(submit_command(3, 2), 0);
  EXPECT_TRUE(vehicle.wait_for([](const auto& got) { return got.size() >= 2; }, 15s)) << daemons_[1]->stderr_text();
  ASSERT_LT(std::time(nullptr), until) << "the overlap ended before both arrived: the machine is too slow";

  // After `until`, key 1 is refused; key 2 still arrives.
  ASSERT_TRUE(wait_until([&] { return std::time(nullptr) > until + 1; }, 30s, 200ms));
  ASSERT_GT(submit_command(3, 3), 0);
  EXPECT_TRUE(wait_until([&] { return counters(1).auth_failed() >= 1; }, 20s, 200ms)) << daemons_[1]->stderr_text();
  EXPECT_NE(daemons_[1]->stderr_text().find("key retired 1"), std::string::npos) << daemons_[1]->stderr_text();
  ASSERT_GT(submit_command(2, 4), 0);
  EXPECT_TRUE(vehicle.wait_for([](const auto& got) { return got.size() >= 3; }, 20s));
  std::vector<int> got = seqs(vehicle.received());
  std::sort(got.begin(), got.end());  // the topside's and the late node's slots come in either order
  EXPECT_EQ(got, (std::vector<int>{1, 2, 4}));
}

}  // namespace
}  // namespace acomms::testing
