// A telemetry gap's packets made packet events (node/unheard_packets.h):
// only those the links did not already record as lost, never for a gap
// told again from the event log at start.
#include "node/unheard_packets.h"

#include <gtest/gtest.h>

#include <map>
#include <vector>

namespace acomms::node {
namespace {

class UnheardPacketsTest : public ::testing::Test {
 protected:
  UnheardPackets unheard_{{[this](int32_t src) { return link_lost_[src]; },
                           [this](int32_t src) { recorded_.push_back(src); },
                           [this](int32_t src) { return several_[src]; }}};
  std::map<int32_t, uint64_t> link_lost_;  // what the links recorded lost, by sender
  std::map<int32_t, bool> several_;        // heard on several links of late, by sender
  std::vector<int32_t> recorded_;          // unheard packet events, by sender
};

TEST_F(UnheardPacketsTest, EachMissingMessageTheLinkDidNotRecordIsOnePacketEvent) {
  unheard_.on_sequence(2, 0, false);  // the stream's first message
  unheard_.on_sequence(2, 3, false);
  EXPECT_EQ(recorded_, (std::vector<int32_t>{2, 2, 2}));
  EXPECT_EQ(unheard_.counters().recorded, 3u);
}

TEST_F(UnheardPacketsTest, LossesTheLinkRecordedSinceTheLastMessageAreNotCountedAgain) {
  unheard_.on_sequence(2, 0, false);
  link_lost_[2] = 2;  // e.g. two damaged packets the Micro-Modem told
  unheard_.on_sequence(2, 3, false);
  EXPECT_EQ(recorded_.size(), 1u) << "3 missing, 2 already lost packet events";
  EXPECT_EQ(unheard_.counters().link_recorded, 2u);
  // More recorded losses than missing messages (other traffic lost too):
  // none recorded, and they do not carry over to the next gap.
  link_lost_[2] = 7;
  unheard_.on_sequence(2, 1, false);
  EXPECT_EQ(recorded_.size(), 1u);
  unheard_.on_sequence(2, 2, false);
  EXPECT_EQ(recorded_.size(), 3u);
  // Another sender's losses are its own.
  unheard_.on_sequence(3, 0, false);
  unheard_.on_sequence(3, 1, false);
  EXPECT_EQ(recorded_.back(), 3);
}

TEST_F(UnheardPacketsTest, AReplayedGapIsNotCountedAgain) {
  unheard_.on_sequence(2, 0, true);
  unheard_.on_sequence(2, 4, true);
  EXPECT_TRUE(recorded_.empty());
  EXPECT_EQ(unheard_.counters().replayed, 4u);
}

// A sender heard on two links: a gap may be messages still in flight on the
// other link (Iridium behind an acoustic newer one), not counted; once it
// is heard on one link only, gaps count again.
TEST_F(UnheardPacketsTest, AGapIsNotCountedWhileTheSenderIsHeardOnSeveralLinks) {
  unheard_.on_sequence(2, 0, false);
  several_[2] = true;
  unheard_.on_sequence(2, 2, false);
  EXPECT_TRUE(recorded_.empty());
  EXPECT_EQ(unheard_.counters().several_links, 2u);
  several_[2] = false;
  unheard_.on_sequence(2, 1, false);
  EXPECT_EQ(recorded_, (std::vector<int32_t>{2}));
}

}  // namespace
}  // namespace acomms::node
