// The raw link log: one stamped line per chunk, escaped, rotated at its bound.

#include "link/raw_log.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace acomms::link {
namespace {

using namespace std::chrono_literals;

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class RawLogTest : public ::testing::Test {
 protected:
  RawLogTest() {
    dir_ = std::filesystem::temp_directory_path() /
           ("raw_log_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~RawLogTest() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
  // 2023-11-14T22:13:20Z
  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
};

TEST_F(RawLogTest, EachChunkIsOneLineStampedToTheMicrosecondWithItsDirection) {
  RawLog log(dir_ / "link-raw.log", 1 << 20, clock_);
  clock_.advance(1234us);
  log.record("$CCCYC,0,1,2,0,1,1*5A", true);
  log.record("$CACYC,0,1,2,0,1,1*58", false);
  EXPECT_EQ(read(dir_ / "link-raw.log"),
            "2023-11-14T22:13:20.001234Z >> $CCCYC,0,1,2,0,1,1*5A\n"
            "2023-11-14T22:13:20.001234Z << $CACYC,0,1,2,0,1,1*58\n");
}

TEST_F(RawLogTest, NonPrintableBytesAndBackslashesAreEscapedSoARecordStaysOneLine) {
  EXPECT_EQ(RawLog::format(clock_.now(), std::string("a\r\n\x00\xff\\", 6), false),
            "2023-11-14T22:13:20.000000Z << a\\x0D\\x0A\\x00\\xFF\\x5C");
}

TEST_F(RawLogTest, RotatesAtTheBoundKeepingOneOlderFile) {
  const std::string line(60, 'x');  // 27 + 4 + 60 + 1 = 92 bytes per record
  RawLog log(dir_ / "link-raw.log", 200, clock_);
  for (int i = 0; i < 7; ++i) log.record(line, false);
  EXPECT_EQ(log.rotations(), 3u);
  EXPECT_LE(std::filesystem::file_size(dir_ / "link-raw.log"), 200u);
  EXPECT_LE(std::filesystem::file_size(dir_ / "link-raw.log.1"), 200u);
  EXPECT_EQ(std::filesystem::file_size(dir_ / "link-raw.log"), 92u);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "link-raw.log.2"));
}

TEST_F(RawLogTest, AnUnwritablePathIsAnErrorNamingIt) {
  try {
    RawLog log(dir_ / "missing" / "link-raw.log", 100, clock_);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing/link-raw.log"), std::string::npos);
  }
}

}  // namespace
}  // namespace acomms::link
