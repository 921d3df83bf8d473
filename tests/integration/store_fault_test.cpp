// The real acommsd when its store's disk refuses writes, and then takes them
// again: Submit answers UNAVAILABLE naming the store, never an id it did not
// store, and the daemon serves on once the disk works.
//
// The fault: the daemon's file-size limit (RLIMIT_FSIZE) lowered, while it
// runs, to the size its write-ahead log already has, so that the next commit
// cannot append to it (EFBIG, an I/O error to SQLite), and raised again
// later. The daemon starts with SIGXFSZ ignored, as the signal would
// otherwise kill it. A full disk (ENOSPC, RESOURCE_EXHAUSTED) needs a small
// filesystem and root to mount it: tests/unit/store injects that one
// through a SQLite VFS instead.

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "acomms/v1/acomms.grpc.pb.h"
#include "child_process.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kAcommsd = ACOMMSD_BINARY;

class StoreFaultTest : public ::testing::Test {
 protected:
  void SetUp() override {
    socket_ = (dir_ / "api.sock").string();
    config_ = (dir_ / "acommsd.conf").string();
    // Another node's slot only: nothing is sent, so the queue changes only
    // by Submit.
    DaemonConfig{.data_dir = dir_ / "data",
                 .unix_socket = socket_,
                 .proto_file = ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto",
                 .rest = "driver { name: \"sim\" modem_id: 3 }\n"
                         "mac { name: \"fixed\" slot { src: 5 seconds: 10 } }\n"}
        .write(config_);
  }

  std::string db_path() const { return (dir_ / "data" / "acommsd.db").string(); }

  grpc::Status submit(v1::Acomms::Stub& stub, int x, int64_t* id) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + 20s);
    v1::SubmitRequest request;
    request.set_type("gv.NavigationReport");
    request.set_json(R"({"x": )" + std::to_string(x) + R"(, "y": 550, "z": -100})");
    v1::SubmitResponse response;
    grpc::Status status = stub.Submit(&context, request, &response);
    *id = response.message_id();
    return status;
  }

  std::set<int64_t> queued(v1::Acomms::Stub& stub) {
    grpc::ClientContext context;
    v1::ListQueuedRequest request;
    v1::ListQueuedResponse response;
    EXPECT_TRUE(stub.ListQueued(&context, request, &response).ok());
    std::set<int64_t> ids;
    for (const auto& m : response.messages()) ids.insert(m.message_id());
    return ids;
  }

  // Short base path: unix socket paths are limited to 107 bytes.
  TempDir dir_{"acomms-sf", "/tmp"};
  std::string socket_;
  std::string config_;
};

void set_file_size_limit(pid_t pid, rlim_t bytes) {
  rlimit limit{};
  ASSERT_EQ(::prlimit(pid, RLIMIT_FSIZE, nullptr, &limit), 0);
  limit.rlim_cur = bytes;
  ASSERT_EQ(::prlimit(pid, RLIMIT_FSIZE, &limit, nullptr), 0) << "cannot change the daemon's file-size limit";
}

TEST_F(StoreFaultTest, ADaemonWhoseStoreCannotWriteAnswersUnavailableAndServesOnceItCan) {
  // sh ignores SIGXFSZ, then becomes the daemon (exec keeps it ignored).
  ChildProcess daemon("/bin/sh", {"-c", "trap '' XFSZ; exec \"$0\" \"$@\"", kAcommsd, "--config", config_},
                      (dir_ / "daemon").string());
  ASSERT_TRUE(testing::wait_serving(daemon, socket_)) << daemon.stderr_text();
  auto stub = api(socket_);
  int64_t first = 0;
  ASSERT_TRUE(submit(*stub, 100, &first).ok());

  // No file may grow past the write-ahead log's present size.
  const auto wal_size = static_cast<rlim_t>(fs::file_size(db_path() + "-wal"));
  ASSERT_GT(wal_size, 0u);
  set_file_size_limit(daemon.pid(), wal_size);
  for (int x = 101; x <= 103; ++x) {
    int64_t id = 0;
    grpc::Status status = submit(*stub, x, &id);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAVAILABLE) << status.error_message();
    EXPECT_NE(status.error_message().find(db_path()), std::string::npos)
        << "does not name the store: " << status.error_message();
    EXPECT_NE(status.error_message().find("not stored"), std::string::npos) << status.error_message();
  }
  EXPECT_EQ(queued(*stub), std::set<int64_t>{first});

  set_file_size_limit(daemon.pid(), RLIM_INFINITY);
  int64_t second = 0;
  grpc::Status status = submit(*stub, 104, &second);
  ASSERT_TRUE(status.ok()) << "the daemon did not recover: " << status.error_message();
  const std::set<int64_t> answered{first, second};
  EXPECT_EQ(queued(*stub), answered);

  daemon.signal(SIGTERM);
  ASSERT_EQ(daemon.wait(15s), std::optional<int>(0)) << daemon.stderr_text();
  // What the daemon answered is what a restarted daemon has queued.
  ChildProcess again(kAcommsd, {"--config", config_}, (dir_ / "again").string());
  ASSERT_TRUE(testing::wait_serving(again, socket_)) << again.stderr_text();
  auto stub_again = api(socket_);
  EXPECT_EQ(queued(*stub_again), answered);
  again.signal(SIGTERM);
  EXPECT_EQ(again.wait(15s), std::optional<int>(0)) << again.stderr_text();
}

}  // namespace
}  // namespace acomms::testing
