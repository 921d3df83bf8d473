// The real acommsd binary, end to end: start on a fresh data dir, health
// SERVING, systemd readiness, `acommsctl status --json`, reflection, SIGTERM
// exit 0 with the schema recorded, and a second start that applies nothing;
// Submit's errors, and SIGTERM in the middle of a stream of Submits.

#include <google/protobuf/util/json_util.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <thread>

#include "acomms/v1/acomms.grpc.pb.h"
#include "child_process.h"
#include "daemon_harness.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "grpc/reflection/v1alpha/reflection.grpc.pb.h"
#include "store/migration.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kAcommsd = ACOMMSD_BINARY;
const std::string kAcommsctl = ACOMMSCTL_BINARY;

// An abstract-namespace datagram socket standing in for systemd's.
class FakeSystemd {
 public:
  FakeSystemd() : name_("acomms-it-" + std::to_string(::getpid())) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::memcpy(addr.sun_path + 1, name_.data(), name_.size());
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&addr),
                     offsetof(sockaddr_un, sun_path) + 1 + name_.size()),
              0);
  }
  ~FakeSystemd() { ::close(fd_); }
  std::string address() const { return "@" + name_; }
  // Everything received so far, messages joined by '|'.
  std::string received() {
    std::string all;
    char buffer[512];
    ssize_t n;
    while ((n = ::recv(fd_, buffer, sizeof(buffer), MSG_DONTWAIT)) > 0) {
      all += (all.empty() ? "" : "|") + std::string(buffer, n);
    }
    return all;
  }

 private:
  std::string name_;
  int fd_;
};

class DaemonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    socket_ = (dir_ / "api.sock").string();
    config_ = (dir_ / "acommsd.conf").string();
    DaemonConfig{.data_dir = dir_ / "data",
                 .unix_socket = socket_,
                 .rest = "log_level: DEBUG\n"
                         "driver { name: \"sim\" modem_id: 3 }\n"
                         "mac { name: \"fixed\" slot { src: 3 seconds: 10 } }\n"}
        .write(config_);
  }

  std::unique_ptr<ChildProcess> start_daemon(const std::string& log_name,
                                             const std::map<std::string, std::string>& env = {}) {
    return std::make_unique<ChildProcess>(kAcommsd, std::vector<std::string>{"--config", config_},
                                          (dir_ / log_name).string(), env);
  }

  bool wait_serving(ChildProcess& daemon, std::chrono::milliseconds timeout = 20s) {
    return testing::wait_serving(daemon, socket_, timeout);
  }

  std::string db_path() const { return (dir_ / "data" / "acommsd.db").string(); }

  // Short base path: unix socket paths are limited to 107 bytes.
  TempDir dir_{"acomms-it", "/tmp"};
  std::string socket_;
  std::string config_;
};

// (version, name, applied_at) rows of schema_migrations, read directly.
std::vector<std::string> migration_rows(const std::string& db_path) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* stmt = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(db,
                               "SELECT version || ' ' || name || ' ' || applied_at "
                               "FROM schema_migrations ORDER BY version",
                               -1, &stmt, nullptr),
            SQLITE_OK);
  std::vector<std::string> rows;
  while (sqlite3_step(stmt) == SQLITE_ROW) {
    rows.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(stmt, 0)));
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return rows;
}

TEST_F(DaemonTest, ServesStatusStopsCleanlyAndRestartsWithoutRemigrating) {
  const int64_t expected_schema = store::known_migrations().back().version;
  FakeSystemd systemd;
  auto daemon = start_daemon("first", {{"NOTIFY_SOCKET", systemd.address()}});
  ASSERT_TRUE(wait_serving(*daemon)) << daemon->stderr_text();
  EXPECT_NE(systemd.received().find("READY=1"), std::string::npos);

  struct stat info {};
  ASSERT_EQ(::stat(socket_.c_str(), &info), 0);
  EXPECT_TRUE(S_ISSOCK(info.st_mode));
  EXPECT_EQ(info.st_mode & 0777, 0660u);

  RunResult status = run(kAcommsctl, {"--socket", socket_, "status", "--json"},
                         (dir_ / "ctl").string());
  ASSERT_EQ(status.exit_code, 0) << status.err;
  v1::Status reported;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(status.out, &reported).ok()) << status.out;
  EXPECT_EQ(reported.version(), ACOMMS_VERSION);
  EXPECT_EQ(reported.data_dir(), (dir_ / "data").string());
  EXPECT_EQ(reported.schema_version(), expected_schema);
  EXPECT_EQ(reported.driver(), "sim");
  EXPECT_EQ(reported.mac(), "fixed");
  EXPECT_EQ(reported.modem_id(), 3u);
  EXPECT_GT(reported.uptime_s(), 0.0);
  EXPECT_LT(reported.uptime_s(), 60.0);

  RunResult human = run(kAcommsctl, {"--socket", socket_, "status"}, (dir_ / "ctl-human").string());
  EXPECT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("schema version:  " + std::to_string(expected_schema)), std::string::npos)
      << human.out;

  daemon->signal(SIGTERM);
  std::optional<int> code = daemon->wait(15s);
  ASSERT_TRUE(code.has_value()) << "no clean exit; signal " << daemon->exit_signal();
  EXPECT_EQ(*code, 0) << daemon->stderr_text();
  EXPECT_NE(systemd.received().find("STOPPING=1"), std::string::npos);
  EXPECT_FALSE(fs::exists(socket_)) << "socket file left behind";

  std::vector<std::string> first_rows = migration_rows(db_path());
  ASSERT_EQ(first_rows.size(), store::known_migrations().size());
  EXPECT_EQ(first_rows.back().substr(0, first_rows.back().find(' ')), std::to_string(expected_schema));
  // The WAL was checkpointed at close: the main file alone holds the data.
  EXPECT_FALSE(fs::exists(db_path() + "-wal") && fs::file_size(db_path() + "-wal") > 0);

  auto second = start_daemon("second");
  ASSERT_TRUE(wait_serving(*second)) << second->stderr_text();
  second->signal(SIGINT);
  ASSERT_EQ(second->wait(15s), std::optional<int>(0)) << second->stderr_text();
  EXPECT_NE(second->stderr_text().find("(0 migrations applied)"), std::string::npos)
      << second->stderr_text();
  EXPECT_EQ(migration_rows(db_path()), first_rows);
}

TEST_F(DaemonTest, ReflectionListsTheServices) {
  auto daemon = start_daemon("reflect");
  ASSERT_TRUE(wait_serving(*daemon)) << daemon->stderr_text();
  auto channel = grpc::CreateChannel("unix:" + socket_, grpc::InsecureChannelCredentials());
  auto reflection = grpc::reflection::v1alpha::ServerReflection::NewStub(channel);
  grpc::ClientContext context;
  auto stream = reflection->ServerReflectionInfo(&context);
  grpc::reflection::v1alpha::ServerReflectionRequest request;
  request.set_list_services("*");
  ASSERT_TRUE(stream->Write(request));
  grpc::reflection::v1alpha::ServerReflectionResponse response;
  ASSERT_TRUE(stream->Read(&response));
  std::set<std::string> names;
  for (const auto& s : response.list_services_response().service()) names.insert(s.name());
  EXPECT_TRUE(names.count("acomms.v1.Acomms")) << response.DebugString();
  EXPECT_TRUE(names.count("grpc.health.v1.Health")) << response.DebugString();

  request.set_file_containing_symbol("acomms.v1.Acomms");
  ASSERT_TRUE(stream->Write(request));
  ASSERT_TRUE(stream->Read(&response));
  ASSERT_GT(response.file_descriptor_response().file_descriptor_proto_size(), 0)
      << response.DebugString();
  stream->WritesDone();
  context.TryCancel();
  daemon->signal(SIGTERM);
  EXPECT_EQ(daemon->wait(15s), std::optional<int>(0));
}

TEST_F(DaemonTest, AcommsctlReportsAnUnreachableDaemonOnOneLine) {
  RunResult missing = run(kAcommsctl, {"--socket", socket_, "status"}, (dir_ / "ctl").string());
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.out, "");
  EXPECT_EQ(missing.err, "acommsctl: cannot reach acommsd at " + socket_ +
                             ": no such socket (is acommsd running? see --socket)\n");

  // A socket file nobody listens on (a daemon that was SIGKILLed).
  int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, socket_.c_str(), sizeof(addr.sun_path) - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
  ::close(fd);
  RunResult stale = run(kAcommsctl, {"--socket", socket_, "--timeout", "1", "status"},
                        (dir_ / "ctl2").string());
  EXPECT_EQ(stale.exit_code, 1);
  EXPECT_EQ(std::count(stale.err.begin(), stale.err.end(), '\n'), 1) << stale.err;
  EXPECT_EQ(stale.err.rfind("acommsctl: cannot reach acommsd at " + socket_, 0), 0u) << stale.err;

  // The daemon replaces such a stale socket instead of failing to bind.
  auto daemon = start_daemon("stale");
  EXPECT_TRUE(wait_serving(*daemon)) << daemon->stderr_text();
}

TEST_F(DaemonTest, CheckConfigAndExampleConfig) {
  RunResult example = run(kAcommsd, {"--example-config"}, (dir_ / "example").string());
  ASSERT_EQ(example.exit_code, 0);
  EXPECT_NE(example.out.find("unix_socket"), std::string::npos);
  std::string example_path = (dir_ / "example.conf").string();
  std::ofstream(example_path) << example.out;
  RunResult check = run(kAcommsd, {"--check-config", example_path}, (dir_ / "check").string());
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_EQ(check.out, example_path + ": ok\n");

  std::string bad_path = (dir_ / "bad.conf").string();
  std::ofstream(bad_path) << "log_level: INFO\ngrpc {\n  tcp_listen: \"nowhere\"\n}\n";
  RunResult bad = run(kAcommsd, {"--check-config", bad_path}, (dir_ / "bad").string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find(bad_path + ":3:3: field 'grpc.tcp_listen'"), std::string::npos) << bad.err;
}

TEST_F(DaemonTest, CheckConfigWarnsOfASlotTooShortForOneFrameAndStillPasses) {
  // Slot 2 is 4 s at rate 5: one frame, its ACK and the travel to 2000 m
  // and back need 4.55 s. Slot 1 (8 s) holds a full packet.
  std::string path = (dir_ / "short.conf").string();
  std::ofstream(path) << "driver { name: \"sim\" modem_id: 1 }\n"
                      << "mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: 8 } slot { src: 2 rate: 5 seconds: 4 } }\n";
  RunResult check = run(kAcommsd, {"--check-config", path}, (dir_ / "check").string());
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_EQ(check.out, path + ": ok\n");
  EXPECT_EQ(check.err,
            "acommsd: warning: " + path +
                ": mac slot 2 (src 2, rate 5, 4 s) cannot carry one frame: one frame needs 4.55 s (air 0.69 s, "
                "turnaround and ACK 1.20 s, travel 2 x 1.33 s for 2000 m), 4.00 s are left\n");

  // With the nodes within 1 km the same slot carries frames: no warning.
  std::ofstream(path) << "driver { name: \"sim\" modem_id: 1 }\n"
                      << "mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: 8 } slot { src: 2 rate: 5 seconds: 4 }\n"
                      << "      max_range_m: 1000 }\n";
  RunResult near = run(kAcommsd, {"--check-config", path}, (dir_ / "near").string());
  EXPECT_EQ(near.exit_code, 0) << near.err;
  EXPECT_EQ(near.err, "");

  // The examples carry full packets: no warning either.
  for (const char* example : {"vehicle.conf", "topside.conf"}) {
    RunResult ok = run(kAcommsd, {"--check-config", std::string(ACOMMS_SOURCE_DIR "/examples/") + example},
                       (dir_ / "example").string());
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
    EXPECT_EQ(ok.err, "") << example;
  }
}

TEST_F(DaemonTest, StartupErrorsExitNonZeroWithTheReason) {
  fs::create_directories(dir_ / "data");
  std::ofstream(db_path()) << std::string(4096, 'x');
  auto daemon = start_daemon("corrupt");
  std::optional<int> code = daemon->wait(15s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 1);
  EXPECT_NE(daemon->stderr_text().find("not a usable SQLite database"), std::string::npos)
      << daemon->stderr_text();

  std::string nope = (dir_ / "nope.conf").string();
  RunResult missing = run(kAcommsd, {"--config", nope}, (dir_ / "missing").string());
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err, "acommsd: " + nope + ": cannot open config file\n");

  // A driver whose settings it refuses when the daemon builds it (udp with
  // no listen address): the start stops what it built and exits, naming it.
  DaemonConfig{.data_dir = dir_ / "data-udp",
               .unix_socket = socket_,
               .rest = "driver { name: \"udp\" modem_id: 3 udp { } }\nmac { name: \"none\" }\n"}
      .write(config_);
  auto refused = start_daemon("udp-refused");
  std::optional<int> refused_code = refused->wait(15s);
  ASSERT_TRUE(refused_code.has_value()) << "acommsd hung after its driver refused its settings";
  EXPECT_EQ(*refused_code, 1);
  EXPECT_NE(refused->stderr_text().find("driver udp"), std::string::npos) << refused->stderr_text();

  RunResult usage = run(kAcommsd, {"--no-such-option"}, (dir_ / "usage").string());
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_NE(usage.err.find("--no-such-option"), std::string::npos) << usage.err;
}

TEST_F(DaemonTest, LoadsDcclDefinitionsFromConfig) {
  const std::string gv = ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto";
  // The configured file's types, plus position telemetry's, which the
  // daemon always loads (api/proto/acomms/telemetry/messages.proto).
  int expected_types = 0;
  for (const std::string& file : {gv, std::string(ACOMMS_SOURCE_DIR "/api/proto/acomms/telemetry/messages.proto")}) {
    std::ifstream proto(file);
    std::string text((std::istreambuf_iterator<char>(proto)), std::istreambuf_iterator<char>());
    for (size_t at = 0; (at = text.find("option (dccl.msg)", at)) != std::string::npos; ++at) ++expected_types;
  }

  std::ofstream(config_, std::ios::app) << "dccl { proto_files: \"" << gv << "\" passphrase: \"x\" }\n";
  auto daemon = start_daemon("dccl");
  ASSERT_TRUE(wait_serving(*daemon)) << daemon->stderr_text();
  RunResult status = run(kAcommsctl, {"--socket", socket_, "--json", "status"}, (dir_ / "ctl").string());
  v1::Status reported;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(status.out, &reported).ok()) << status.out;
  EXPECT_EQ(reported.dccl_types(), expected_types);
  EXPECT_NE(daemon->stderr_text().find("dccl: bodies encrypted"), std::string::npos);
}

TEST_F(DaemonTest, BrokenDcclDefinitionsStopTheStart) {
  std::string bad = (dir_ / "bad.proto").string();
  std::ofstream(bad) << "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\n"
                        "message Bad {\n  option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 8 };\n"
                        "  required string s = 1;\n}\n";
  std::ofstream(config_, std::ios::app) << "dccl { proto_files: \"" << bad << "\" }\n";
  auto daemon = start_daemon("bad-dccl");
  std::optional<int> code = daemon->wait(15s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 1);
  EXPECT_NE(daemon->stderr_text().find("Bad.s"), std::string::npos) << daemon->stderr_text();
  EXPECT_NE(daemon->stderr_text().find("max_length"), std::string::npos) << daemon->stderr_text();
}

// Submit through the real daemon: durable ids, every error status, and the
// queued message still there after a restart.
TEST_F(DaemonTest, SubmitQueuesDurablyAndRefusesBadInputClearly) {
  const std::string gv = ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto";
  std::ofstream(config_, std::ios::app)
      << "dccl { proto_files: \"" << gv << "\" strict: true }\n"
      << "queue { type { type: \"gv.Num4\" policy { max_queue: 1 on_full: REFUSE_NEW } } }\n";
  auto daemon = start_daemon("submit");
  ASSERT_TRUE(wait_serving(*daemon)) << daemon->stderr_text();
  auto stub = v1::Acomms::NewStub(grpc::CreateChannel("unix:" + socket_, grpc::InsecureChannelCredentials()));
  auto submit = [&](const std::string& type, const std::string& json, v1::SubmitResponse* response) {
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type(type);
    request.set_json(json);
    return stub->Submit(&context, request, response);
  };
  v1::SubmitResponse ok;
  grpc::Status status = submit("gv.NavigationReport", R"({"x": 450, "y": 550, "z": -100})", &ok);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_GT(ok.message_id(), 0);

  v1::SubmitResponse ignored;
  status = submit("gv.Nope", "{}", &ignored);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(status.error_message(), "no DCCL type \"gv.Nope\" is loaded");

  status = submit("gv.NavigationReport", R"({"x": 450, "y": 550, "z": 1})", &ignored);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("gv.NavigationReport.z"), std::string::npos) << status.error_message();

  status = submit("gv.NavigationReport", R"({"x": 450})", &ignored);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  // Checked once the queue's roles had their chance to fill fields: every
  // missing one is named.
  EXPECT_EQ(status.error_message(), "gv.NavigationReport: required field(s) missing: y, z");
  {
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type("gv.NavigationReport");
    request.set_payload(std::string("\x09", 1) + std::string(8, '\0'));  // x only, as protobuf
    status = stub->Submit(&context, request, &ignored);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_EQ(status.error_message(), "gv.NavigationReport: required field(s) missing: y, z");
  }

  status = submit("gv.NavigationReport", R"({"x": "not a number"})", &ignored);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message().rfind("json: ", 0), 0u) << status.error_message();

  ASSERT_TRUE(submit("gv.Num4", R"({"ri": 1, "ru": 1})", &ignored).ok());
  status = submit("gv.Num4", R"({"ri": 2, "ru": 2})", &ignored);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(status.error_message(), "queue gv.Num4 is full (max_queue 1) and refuses new messages");

  daemon->signal(SIGTERM);
  ASSERT_EQ(daemon->wait(15s), std::optional<int>(0)) << daemon->stderr_text();
  auto again = start_daemon("submit-again");
  ASSERT_TRUE(wait_serving(*again)) << again->stderr_text();
  EXPECT_NE(again->stderr_text().find("2 messages restored from the store"), std::string::npos)
      << "before the restart:\n" << daemon->stderr_text() << "after:\n" << again->stderr_text();
}

// SIGTERM while clients are submitting as fast as they can: Submits are
// answered from the store writer's commit and the core thread, not from a
// parked gRPC thread, so stopping must still wait for every call in flight,
// exit 0, and lose none of the messages whose Submit returned OK.
TEST_F(DaemonTest, SigtermUnderSubmitLoadExitsCleanlyAndLosesNothing) {
  const std::string gv = ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto";
  // The only slot is another node's: a message sent in a slot of our own
  // would leave the queue and look lost.
  DaemonConfig{.data_dir = dir_ / "data",
               .unix_socket = socket_,
               .proto_file = gv,
               .rest = "driver { name: \"sim\" modem_id: 3 }\n"
                       "mac { name: \"fixed\" slot { src: 5 seconds: 10 } }\n"
                       "queue { type { type: \"gv.NavigationReport\" policy { max_queue: 100000 } } }\n"}
      .write(config_);
  auto daemon = start_daemon("load");
  ASSERT_TRUE(wait_serving(*daemon)) << daemon->stderr_text();

  constexpr int kClients = 4;
  constexpr int kMostEach = 2000;  // stays under ListQueued's 10000
  std::vector<std::vector<int64_t>> acknowledged(kClients);
  std::vector<std::vector<grpc::StatusCode>> refused(kClients);
  // SIGTERM goes once the load is real (not after a fixed sleep, which a
  // busy machine can fill with start-up alone).
  std::atomic<int> acknowledged_total{0};
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([&, c] {
      grpc::ChannelArguments args;
      args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);  // a connection each
      auto stub = v1::Acomms::NewStub(
          grpc::CreateCustomChannel("unix:" + socket_, grpc::InsecureChannelCredentials(), args));
      for (int i = 0; i < kMostEach; ++i) {
        grpc::ClientContext context;
        context.set_deadline(std::chrono::system_clock::now() + 20s);
        v1::SubmitRequest request;
        request.set_type("gv.NavigationReport");
        request.set_json("{\"x\": " + std::to_string(c) + ", \"y\": " + std::to_string(i) + ", \"z\": -1}");
        v1::SubmitResponse response;
        grpc::Status status = stub->Submit(&context, request, &response);
        if (!status.ok()) {
          refused[c].push_back(status.error_code());
          break;  // the daemon is going away
        }
        acknowledged[c].push_back(response.message_id());
        ++acknowledged_total;
      }
    });
  }
  EXPECT_TRUE(wait_until([&] { return acknowledged_total.load() >= 400; }, 20s));
  daemon->signal(SIGTERM);
  for (auto& client : clients) client.join();
  ASSERT_EQ(daemon->wait(15s), std::optional<int>(0)) << daemon->stderr_text();

  std::set<int64_t> ok_ids;
  for (const auto& ids : acknowledged) ok_ids.insert(ids.begin(), ids.end());
  ASSERT_GT(ok_ids.size(), 100u) << "too little load to mean anything";
  for (const auto& codes : refused) {
    for (grpc::StatusCode code : codes) {
      // Refused because the daemon is stopping, never as if the input were bad.
      EXPECT_TRUE(code == grpc::StatusCode::UNAVAILABLE || code == grpc::StatusCode::CANCELLED) << code;
    }
  }

  auto again = start_daemon("load-again");
  ASSERT_TRUE(wait_serving(*again)) << again->stderr_text();
  auto stub = v1::Acomms::NewStub(grpc::CreateChannel("unix:" + socket_, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  v1::ListQueuedRequest request;
  request.set_type("gv.NavigationReport");
  request.set_limit(10000);
  v1::ListQueuedResponse queued;
  ASSERT_TRUE(stub->ListQueued(&context, request, &queued).ok());
  std::set<int64_t> restored;
  for (const auto& message : queued.messages()) restored.insert(message.message_id());
  std::vector<int64_t> lost;
  std::set_difference(ok_ids.begin(), ok_ids.end(), restored.begin(), restored.end(), std::back_inserter(lost));
  EXPECT_TRUE(lost.empty()) << lost.size() << " of " << ok_ids.size()
                            << " acknowledged messages are gone, first id " << lost.front();
}

TEST_F(DaemonTest, SecondDaemonOnTheSameDataDirIsRefused) {
  auto first = start_daemon("one");
  ASSERT_TRUE(wait_serving(*first)) << first->stderr_text();
  auto second = start_daemon("two");
  std::optional<int> code = second->wait(15s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 1);
  EXPECT_NE(second->stderr_text().find("in use by another acommsd"), std::string::npos)
      << second->stderr_text();
  EXPECT_TRUE(first->running());
}

// A start that fails after the link is up (here the TCP port is taken)
// stops the link on the core thread first: exit 1 with the reason, not an
// abort on the core-thread assertion.
TEST_F(DaemonTest, TakenTcpPortExitsWithTheReasonAfterTheLinkStarted) {
  const int port = free_tcp_port();
  int holder = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(holder, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(holder, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(holder, 1), 0);
  DaemonConfig{.data_dir = dir_ / "data",
               .unix_socket = socket_,
               .grpc_extra = "tcp_listen: \"127.0.0.1:" + std::to_string(port) + "\" insecure_tcp: true",
               .rest = "driver { name: \"sim\" modem_id: 3 }\n"
                       "mac { name: \"fixed\" slot { src: 3 seconds: 10 } }\n"}
      .write(config_);
  auto daemon = start_daemon("port_taken");
  std::optional<int> code = daemon->wait(15s);
  ::close(holder);
  ASSERT_TRUE(code.has_value()) << daemon->stderr_text();
  EXPECT_EQ(*code, 1) << daemon->stderr_text();
  EXPECT_NE(daemon->stderr_text().find(std::to_string(port)), std::string::npos) << daemon->stderr_text();
  EXPECT_EQ(daemon->stderr_text().find("must run on the core thread"), std::string::npos)
      << daemon->stderr_text();
}

}  // namespace
}  // namespace acomms::testing
