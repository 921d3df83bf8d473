// Three real acommsd processes share the simulated acoustic channel over
// loopback, with fixed TDMA (one 3 s slot each at Micro-Modem rate 5). Each
// submits a broadcast status message; each must receive the other two's,
// which the receiver's event log (in its SQLite store) records.

#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "child_process.h"
#include "net_status_proto.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;


// Sources of the net.Status messages this node's store says it received.
std::set<int> received_from(const std::string& db_path) {
  std::set<int> sources;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    return sources;
  }
  sqlite3_busy_timeout(db, 1000);
  sqlite3_stmt* stmt = nullptr;
  if (sqlite3_prepare_v2(db,
                         "SELECT DISTINCT src FROM event_log WHERE kind = 'received' AND type = 'net.Status'",
                         -1, &stmt, nullptr) == SQLITE_OK) {
    while (sqlite3_step(stmt) == SQLITE_ROW) sources.insert(sqlite3_column_int(stmt, 0));
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return sources;
}

TEST(ThreeNodeLoopback, EveryStatusReachesTheOtherTwo) {
  fs::path dir = fs::path("/tmp") / ("acomms-3n-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "net.proto") << kNetStatusProto;

  const std::vector<int> ids = {1, 2, 3};
  std::map<int, int> port;
  for (int id : ids) port[id] = free_udp_port();

  std::map<int, std::unique_ptr<ChildProcess>> daemons;
  for (int id : ids) {
    std::string name = "node" + std::to_string(id);
    std::ofstream config(dir / (name + ".conf"));
    config << DaemonConfig{.data_dir = dir / name,
                           .unix_socket = (dir / (name + ".sock")).string(),
                           .proto_file = (dir / "net.proto").string()}.text()
           << "queue { type { type: \"net.Status\" roles { source_field: \"src\" destination_field: \"dest\" } } }\n"
           << "driver { name: \"sim\" modem_id: " << id << " sim { position { x: " << 300 * id << " }"
           << " listen: \"127.0.0.1:" << port[id] << "\"";
    for (int other : ids) {
      if (other != id) config << " peers: \"127.0.0.1:" << port[other] << "\"";
    }
    config << " } }\n"
           << "mac { name: \"fixed\"";
    for (int slot : ids) config << " slot { src: " << slot << " rate: 5 seconds: 3 }";
    // At most 600 m apart: the guard for the default 2000 m would leave a
    // 3 s slot at rate 5 no room for one frame and its ACK.
    config << " max_range_m: 600 }\n";
    config.close();
    daemons[id] = std::make_unique<ChildProcess>(ACOMMSD_BINARY,
                                                 std::vector<std::string>{"--config", (dir / (name + ".conf")).string()},
                                                 (dir / name).string());
  }
  for (int id : ids) {
    ASSERT_TRUE(wait_serving(*daemons[id], (dir / ("node" + std::to_string(id) + ".sock")).string()))
        << daemons[id]->stderr_text();
  }
  for (int id : ids) {
    auto stub = api((dir / ("node" + std::to_string(id) + ".sock")).string());
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type("net.Status");
    request.set_json(R"({"src": )" + std::to_string(id) + R"(, "dest": 0, "battery": )" + std::to_string(50 + id) + "}");
    v1::SubmitResponse response;
    grpc::Status status = stub->Submit(&context, request, &response);
    ASSERT_TRUE(status.ok()) << status.error_message();
  }

  // Two 9 s cycles are enough for every node's slot to come round; allow more.
  std::map<int, std::set<int>> heard;
  auto all_heard = [&] {
    for (int id : ids) {
      heard[id] = received_from((dir / ("node" + std::to_string(id)) / "acommsd.db").string());
      std::set<int> others;
      for (int other : ids) {
        if (other != id) others.insert(other);
      }
      if (heard[id] != others) return false;
    }
    return true;
  };
  wait_until(all_heard, 45s, 500ms);
  for (int id : ids) {
    std::set<int> others;
    for (int other : ids) {
      if (other != id) others.insert(other);
    }
    EXPECT_EQ(heard[id], others) << "node " << id << " log:\n" << daemons[id]->stderr_text();
  }
  for (int id : ids) {
    daemons[id]->signal(SIGTERM);
    EXPECT_EQ(daemons[id]->wait(15s), std::optional<int>(0)) << daemons[id]->stderr_text();
  }
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms::testing
