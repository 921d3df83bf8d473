// The test helpers themselves: a TempDir is fresh and gone afterwards, the
// daemon config's head is exact, and wait_until stops as soon as its
// condition holds or fails after its timeout.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "daemon_config.h"
#include "temp_dir.h"
#include "wait_until.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

TEST(TempDir, IsCreatedEmptyAndRemovedWithItsContents) {
  fs::path kept;
  {
    TempDir dir("support-test");
    kept = dir.path();
    ASSERT_TRUE(fs::is_directory(kept));
    EXPECT_TRUE(fs::is_empty(kept));
    fs::create_directories(dir / "a" / "b");
    std::ofstream(dir / "a" / "b" / "file") << "x";
  }
  EXPECT_FALSE(fs::exists(kept));
}

TEST(TempDir, TwoInOneProcessAreDistinct) {
  TempDir one("support-test"), two("support-test");
  EXPECT_NE(one.path(), two.path());
  EXPECT_EQ(one.path().parent_path(), fs::temp_directory_path());
  TempDir in_tmp("support-test", "/tmp");
  EXPECT_EQ(in_tmp.path().parent_path(), fs::path("/tmp"));
}

TEST(DaemonConfig, WritesTheHeadThenTheRest) {
  DaemonConfig config{.data_dir = "/d/data", .unix_socket = "/d/api.sock", .rest = "log_level: DEBUG\n"};
  EXPECT_EQ(config.text(), "data_dir: \"/d/data\"\ngrpc { unix_socket: \"/d/api.sock\" }\nlog_level: DEBUG\n");
  config.proto_file = "/p/m.proto";
  config.grpc_extra = "tcp_listen: \"127.0.0.1:5\"";
  EXPECT_EQ(config.text(),
            "data_dir: \"/d/data\"\ngrpc { unix_socket: \"/d/api.sock\" tcp_listen: \"127.0.0.1:5\" }\n"
            "dccl { proto_files: \"/p/m.proto\" }\nlog_level: DEBUG\n");
  TempDir dir("support-test");
  config.write(dir / "acommsd.conf");
  std::ifstream in(dir / "acommsd.conf");
  std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(written, config.text());
  EXPECT_THROW(config.write(dir / "missing" / "acommsd.conf"), std::runtime_error);
}

TEST(WaitUntil, TrueAsSoonAsTheConditionHolds) {
  int asked = 0;
  EXPECT_TRUE(wait_until([&] { return ++asked == 3; }, 10s, 1ms));
  EXPECT_EQ(asked, 3);
}

TEST(WaitUntil, FalseAfterTheTimeoutHavingAskedAgainAfterTheLastSleep) {
  int asked = 0;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(wait_until([&] { return ++asked < 0; }, 50ms, 10ms));
  EXPECT_GE(std::chrono::steady_clock::now() - start, 50ms);
  EXPECT_GE(asked, 2);
}

}  // namespace
}  // namespace acomms::testing
