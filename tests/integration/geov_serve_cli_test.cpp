// `acommsctl geov serve`'s refusals at the start, the real binary: a
// --listen other machines can reach needs a token (or --insecure-http), a
// token must be worth the name, and a daemon that cannot be reached at the
// start is named at once (exit 1) rather than served as an empty map.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "child_process.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;

class GeovServeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-geov-cli-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  RunResult serve(std::vector<std::string> args) {
    args.insert(args.begin(), {"--socket", (dir_ / "absent.sock").string(), "geov", "serve"});
    return run(ACOMMSCTL_BINARY, args, (dir_ / ("run" + std::to_string(++runs_))).string());
  }
  fs::path dir_;
  int runs_ = 0;
};

TEST_F(GeovServeCli, ANonLoopbackListenWithoutATokenIsRefusedUnlessInsecureHttp) {
  RunResult refused = serve({"--listen", "0.0.0.0:0"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--listen 0.0.0.0:0 is reachable from other machines: give --token-file"),
            std::string::npos)
      << refused.err;
  // With --insecure-http it gets as far as the daemon, which is absent.
  RunResult open = serve({"--listen", "0.0.0.0:0", "--insecure-http"});
  EXPECT_EQ(open.exit_code, 1);
  EXPECT_NE(open.err.find("cannot reach acommsd at"), std::string::npos) << open.err;
  // Loopback needs neither.
  RunResult loopback = serve({"--listen", "127.0.0.1:0"});
  EXPECT_EQ(loopback.exit_code, 1);
  EXPECT_NE(loopback.err.find("cannot reach acommsd at"), std::string::npos) << loopback.err;
}

TEST_F(GeovServeCli, ATokenMustBeLongAndPlain) {
  std::ofstream(dir_ / "short") << "abc\n";
  RunResult short_token = serve({"--listen", "0.0.0.0:0", "--token-file", (dir_ / "short").string()});
  EXPECT_EQ(short_token.exit_code, 2);
  EXPECT_NE(short_token.err.find("16 characters or more"), std::string::npos) << short_token.err;
  std::ofstream(dir_ / "odd") << "0123456789abcdef<script>\n";
  RunResult odd = serve({"--listen", "0.0.0.0:0", "--token-file", (dir_ / "odd").string()});
  EXPECT_EQ(odd.exit_code, 2);
  EXPECT_NE(odd.err.find("only letters, digits"), std::string::npos) << odd.err;
  std::ofstream(dir_ / "good") << "0123456789abcdef-_.XYZ\n";
  RunResult good = serve({"--listen", "0.0.0.0:0", "--token-file", (dir_ / "good").string()});
  EXPECT_EQ(good.exit_code, 1);  // past the token, to the absent daemon
  EXPECT_NE(good.err.find("cannot reach acommsd at"), std::string::npos) << good.err;
}

TEST_F(GeovServeCli, AListenAddressThatCannotBeBoundIsNamed) {
  RunResult bad = serve({"--listen", "no-port"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--listen no-port: want HOST:PORT"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace acomms::testing
