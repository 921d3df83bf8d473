// The example fleet (examples/fleet) as its users run it: `acommsctl fleet
// check|render|import`, and five real acommsd processes started with
// `--fleet FILE --node NAME` on the loopback sim channel, a status from two
// vehicles reaching the shore. The fleet is copied to a fresh directory with
// free UDP ports in place of its fixed ones (4720N).

#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "child_process.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::vector<std::string> kNodes = {"shore", "buoy", "auv_1", "auv_2", "glider_1"};

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::set<int> statuses_received(const std::string& db_path) {
  std::set<int> sources;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_busy_timeout(db, 1000);
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_prepare_v2(db, "SELECT DISTINCT src FROM event_log WHERE kind = 'received' AND type = 'example.Status'",
                           -1, &stmt, nullptr) == SQLITE_OK) {
      while (sqlite3_step(stmt) == SQLITE_ROW) sources.insert(sqlite3_column_int(stmt, 0));
    }
    sqlite3_finalize(stmt);
  }
  sqlite3_close(db);
  return sources;
}

class ExampleFleet : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-fleet-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "fleet");
    fs::copy_file(ACOMMS_SOURCE_DIR "/examples/messages.proto", dir_ / "messages.proto");
    std::map<std::string, std::string> port;
    for (int n = 1; n <= 5; ++n) port["4720" + std::to_string(n)] = std::to_string(free_udp_port());
    for (const char* file : {"fleet.conf", "cruise.conf", "classes.conf"}) {
      std::string text = slurp(fs::path(ACOMMS_SOURCE_DIR "/examples/fleet") / file);
      for (const auto& [fixed, free] : port) text = std::regex_replace(text, std::regex(":" + fixed + "\""), ":" + free + "\"");
      std::ofstream(dir_ / "fleet" / file) << text;
    }
    fleet_ = (dir_ / "fleet" / "fleet.conf").string();
  }
  void TearDown() override {
    if (!::testing::Test::HasFailure()) fs::remove_all(dir_);
  }
  RunResult ctl(const std::vector<std::string>& args) {
    return run(ACOMMSCTL_BINARY, args, (dir_ / ("ctl-" + std::to_string(++runs_))).string());
  }
  fs::path dir_;
  std::string fleet_;
  int runs_ = 0;
};

TEST_F(ExampleFleet, FiveDaemonsRunFromOneFleetFileAndTheShoreHearsTheVehicles) {
  RunResult check = ctl({"fleet", "check", fleet_});
  ASSERT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("5 nodes, no findings: may launch"), std::string::npos) << check.out;

  std::map<std::string, std::unique_ptr<ChildProcess>> daemons;
  auto socket = [&](const std::string& node) { return (dir_ / "fleet/var" / node / "acommsd.sock").string(); };
  for (const std::string& node : kNodes) {
    fs::create_directories(dir_ / "fleet/var" / node);
    daemons[node] = std::make_unique<ChildProcess>(ACOMMSD_BINARY, std::vector<std::string>{"--fleet", fleet_, "--node", node},
                                                   (dir_ / node).string());
  }
  for (const std::string& node : kNodes) {
    ASSERT_TRUE(wait_serving(*daemons[node], socket(node))) << node << ":\n" << daemons[node]->stderr_text();
  }
  const std::map<std::string, int> senders = {{"auv_1", 3}, {"glider_1", 5}};
  const long now = std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  for (const auto& [node, id] : senders) {
    auto stub = api(socket(node));
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type("example.Status");
    request.set_json(R"({"src": )" + std::to_string(id) + R"(, "dest": 0, "time": )" + std::to_string(now) +
                     R"(, "x": 10, "y": 20, "depth": 5})");
    v1::SubmitResponse response;
    grpc::Status status = stub->Submit(&context, request, &response);
    ASSERT_TRUE(status.ok()) << node << ": " << status.error_message();
  }
  // One cycle is 15 s (five 3 s slots); allow three.
  const std::string shore_db = (dir_ / "fleet/var/shore/acommsd.db").string();
  wait_until([&] { return statuses_received(shore_db) == std::set<int>{3, 5}; }, 45s, 500ms);
  EXPECT_EQ(statuses_received(shore_db), (std::set<int>{3, 5})) << daemons["shore"]->stderr_text();
  // Checked at sea: the cruise level enables the announce with the fleet's
  // expected digest, which every node has: the shore hears the others agree.
  v1::Status shore_status;
  wait_until(
      [&] {
        grpc::ClientContext context;
        shore_status.Clear();
        api(socket("shore"))->GetStatus(&context, v1::GetStatusRequest(), &shore_status);
        return shore_status.consistency_size() >= 2;
      },
      30s, 500ms);
  EXPECT_EQ(shore_status.consistency_digest(), "9d3fc24b");
  EXPECT_GE(shore_status.consistency_size(), 2) << shore_status.DebugString();
  for (const v1::NodeConsistency& heard : shore_status.consistency()) {
    EXPECT_TRUE(heard.agrees()) << heard.DebugString();
    EXPECT_EQ(heard.digest(), "9d3fc24b");
  }
  EXPECT_EQ(shore_status.unexpected_digests(), 0u);
  for (auto& [node, daemon] : daemons) {
    daemon->signal(SIGTERM);
    EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << node << ":\n" << daemon->stderr_text();
  }
}

TEST_F(ExampleFleet, RenderedConfigsImportedAndRenderedAgainAreTheSame) {
  std::vector<std::string> files;
  std::map<std::string, std::string> rendered;
  for (const std::string& node : kNodes) {
    RunResult result = ctl({"fleet", "render", node, "-f", fleet_});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    rendered[node] = result.out;
    fs::path file = dir_ / (node + ".conf");
    std::ofstream(file) << result.out;
    files.push_back(file.string());
    // Each rendered config is a config acommsd accepts on its own.
    RunResult checked = run(ACOMMSD_BINARY, {"--check-config", file.string()}, (dir_ / ("check-" + node)).string());
    EXPECT_EQ(checked.exit_code, 0) << node << ": " << checked.err;
  }
  std::vector<std::string> import_args = {"fleet", "import"};
  import_args.insert(import_args.end(), files.begin(), files.end());
  RunResult imported = ctl(import_args);
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_NE(imported.out.find("name: \"common\""), std::string::npos) << imported.out;
  const fs::path again = dir_ / "imported.conf";
  std::ofstream(again) << imported.out;
  for (const std::string& node : kNodes) {
    RunResult result = ctl({"fleet", "render", node, "-f", again.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out, rendered[node]) << node;
  }
}

TEST_F(ExampleFleet, ExplainNamesTheFileAndLineOfEachField) {
  RunResult result = ctl({"fleet", "render", "auv_1", "-f", fleet_, "--explain"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string fleet_dir = (dir_ / "fleet").string();
  // modem_id is the node's own (fleet.conf), the cycle the cruise's, z the class's.
  EXPECT_NE(result.out.find("modem_id: 3  # " + fleet_dir + "/fleet.conf:"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("name: \"fixed\"  # " + fleet_dir + "/cruise.conf:"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("z: 30  # " + fleet_dir + "/classes.conf:"), std::string::npos) << result.out;
  RunResult ls = ctl({"fleet", "ls", fleet_});
  ASSERT_EQ(ls.exit_code, 0) << ls.err;
  EXPECT_NE(ls.out.find("auv_1            3        cruise > global > torpedo"), std::string::npos) << ls.out;
}

TEST_F(ExampleFleet, AcommsdRefusesAClassAnUnknownNodeAndABadFieldNamingTheFleetLine) {
  RunResult a_class = run(ACOMMSD_BINARY, {"--fleet", fleet_, "--node", "torpedo"}, (dir_ / "class").string());
  EXPECT_EQ(a_class.exit_code, 1);
  EXPECT_NE(a_class.err.find("classes.conf:"), std::string::npos) << a_class.err;
  EXPECT_NE(a_class.err.find("is a class, not a node"), std::string::npos) << a_class.err;
  RunResult nobody = run(ACOMMSD_BINARY, {"--fleet", fleet_, "--node", "nobody"}, (dir_ / "nobody").string());
  EXPECT_EQ(nobody.exit_code, 1);
  EXPECT_NE(nobody.err.find("no node \"nobody\""), std::string::npos) << nobody.err;
  const fs::path bad = dir_ / "fleet" / "bad.conf";
  std::ofstream(bad) << "include: \"fleet.conf\"\n"
                        "node { name: \"auv_9\" parent: \"torpedo\"\n"
                        "  config { grpc { tcp_listen: \"nonsense\" } } }\n";
  RunResult field = run(ACOMMSD_BINARY, {"--fleet", bad.string(), "--node", "auv_9"}, (dir_ / "field").string());
  EXPECT_EQ(field.exit_code, 1);
  EXPECT_NE(field.err.find(bad.string() + ":3:"), std::string::npos) << field.err;
  EXPECT_NE(field.err.find("grpc.tcp_listen"), std::string::npos) << field.err;
  RunResult both = run(ACOMMSD_BINARY, {"--fleet", fleet_, "--config", "x.conf", "--node", "auv_1"}, (dir_ / "both").string());
  EXPECT_EQ(both.exit_code, 2) << both.err;
}

TEST(FleetCheckCli, ThePlantedFleetMayNotLaunchAndEachKindIsListed) {
  const fs::path log = fs::path("/tmp") / ("acomms-fleet-check-" + std::to_string(::getpid()));
  RunResult result = run(ACOMMSCTL_BINARY, {"fleet", "check", ACOMMS_SOURCE_DIR "/tests/fleet/planted/fleet.conf"}, log.string());
  EXPECT_EQ(result.exit_code, 1) << result.out << result.err;
  for (const char* kind : {": dccl-id: ", ": dccl-version: ", ": mac-cycle: ", ": slot-source: ", ": modem-id: ",
                           ": route-dest: ", ": route-loop: ", ": key: ", ": slot-short: "}) {
    EXPECT_NE(result.out.find(kind), std::string::npos) << kind << "\n" << result.out;
  }
  EXPECT_NE(result.out.find("9 findings: do not launch"), std::string::npos) << result.out;
  fs::remove(log.string() + ".out");
  fs::remove(log.string() + ".err");
}

}  // namespace
}  // namespace acomms::testing
