// The driver's AT channel: one command at a time, what ends each kind, and
// unsolicited lines that come whenever the modem likes, even cut across
// the end of one command and the start of the next.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "core/scheduler.h"
#include "iridium/at_channel.h"

namespace acomms::drivers::iridium {
namespace {

using namespace std::chrono_literals;
using End = AtChannel::Reply::End;

struct ChannelTest : ::testing::Test {
  core::SimulatedScheduler scheduler{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  std::string written;
  std::vector<AtLine> unsolicited;
  AtChannel channel{scheduler, [this](std::string_view b) { return written.append(b), true; },
                    [this](const AtLine& line) { unsolicited.push_back(line); }};
};

TEST_F(ChannelTest, AnUnsolicitedLineCutAcrossTwoCommandsIsReadWhole) {
  std::optional<AtChannel::Reply> second;
  channel.send("AT\r", "AT", AtChannel::Expect::kFinal, 5s, [&](AtChannel::Reply reply) {
    ASSERT_EQ(reply.end, End::kOk);
    channel.send("AT+SBDD0\r", "AT+SBDD0", AtChannel::Expect::kResult, 5s,
                 [&](AtChannel::Reply r) { second = std::move(r); });
  });
  channel.on_bytes("\r\nOK\r\n+CIEV:0,");
  channel.on_bytes("3\r\n");  // not an SBD result digit 3: the end of +CIEV:0,3
  EXPECT_FALSE(second.has_value());
  ASSERT_EQ(unsolicited.size(), 1u);
  EXPECT_EQ(unsolicited[0].indicator.value, 3);
  channel.on_bytes("\r\n0\r\n\r\nOK\r\n");
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->end, End::kOk);
  EXPECT_EQ(second->digit, 0);
}

TEST_F(ChannelTest, ResultOneOfSbdwbEndsWithoutOkAndEchoIsSkippedAndFlagged) {
  std::optional<AtChannel::Reply> reply;
  channel.send("AT+SBDWB=5\r", "AT+SBDWB=5", AtChannel::Expect::kReady, 5s, [&](AtChannel::Reply r) { reply = r; });
  channel.on_bytes("AT+SBDWB=5\r\r\nREADY\r\n");
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->end, End::kReady);
  EXPECT_TRUE(channel.echo_seen());
  reply.reset();
  channel.send("hello\x02\x14", "", AtChannel::Expect::kResult, 65s, [&](AtChannel::Reply r) { reply = r; });
  channel.on_bytes("\r\n1\r\n");
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->end, End::kDigit);
  EXPECT_EQ(reply->digit, 1);
}

TEST_F(ChannelTest, NumericCodesEndACommandAndAreFlaggedAndSilenceTimesOut) {
  std::optional<AtChannel::Reply> reply;
  channel.send("ATV1\r", "ATV1", AtChannel::Expect::kFinal, 5s, [&](AtChannel::Reply r) { reply = r; });
  channel.on_bytes("0\r");
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->end, End::kOk);
  EXPECT_TRUE(channel.numeric_seen());
  reply.reset();
  channel.send("AT+SBDIX\r", "AT+SBDIX", AtChannel::Expect::kFinal, 90s, [&](AtChannel::Reply r) { reply = r; });
  scheduler.run_for(89s);
  EXPECT_FALSE(reply.has_value());
  scheduler.run_for(2s);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->end, End::kTimeout);
  EXPECT_EQ(channel.counters().timeouts, 1u);
}

}  // namespace
}  // namespace acomms::drivers::iridium
