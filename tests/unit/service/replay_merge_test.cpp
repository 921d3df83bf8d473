// Subscribe's replay merges received messages and telemetry Positions, two
// pages numbered in one sequence (service/replay_merge.h).
#include "service/replay_merge.h"

#include <gtest/gtest.h>

#include <vector>

namespace acomms::service {
namespace {

// The seqs the picks stand for, in the order they are sent.
std::vector<int64_t> sent(const std::vector<int64_t>& messages, bool messages_full,
                          const std::vector<int64_t>& positions, bool positions_full) {
  std::vector<int64_t> out;
  for (const ReplayPick& pick : merge_replay_pages(messages, messages_full, positions, positions_full)) {
    out.push_back(pick.position ? positions.at(pick.index) : messages.at(pick.index));
  }
  return out;
}

TEST(ReplayMerge, InterleavesTwoPartialPagesInSeqOrder) {
  EXPECT_EQ(sent({1, 4, 5, 9}, false, {2, 3, 6, 7, 8}, false), (std::vector<int64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST(ReplayMerge, OnePageAloneIsSentWhole) {
  EXPECT_EQ(sent({}, false, {3, 4}, true), (std::vector<int64_t>{3, 4}));
  EXPECT_EQ(sent({7, 8}, true, {}, false), (std::vector<int64_t>{7, 8}));
}

TEST(ReplayMerge, AFullPageStopsTheOtherAtItsLastSeq) {
  // The messages page is full at 5: a message 6 may exist unread, so
  // positions 6 and 7 wait for the next read, which starts after 5.
  EXPECT_EQ(sent({1, 3, 5}, true, {2, 6, 7}, false), (std::vector<int64_t>{1, 2, 3, 5}));
  // And the other way round.
  EXPECT_EQ(sent({4, 10}, false, {1, 2, 3}, true), (std::vector<int64_t>{1, 2, 3}));
}

TEST(ReplayMerge, TwoFullPagesStopAtTheLowerEnd) {
  EXPECT_EQ(sent({1, 4, 8}, true, {2, 3, 5}, true), (std::vector<int64_t>{1, 2, 3, 4, 5}));
}

TEST(ReplayMerge, ReadsThatFollowTheLastSentSeqCoverEverythingOnce) {
  // 600 seqs, every third a message, in pages of 16: reading after the
  // last seq sent, as Subscribe does, sends each seq once, in order.
  std::vector<int64_t> all_messages, all_positions;
  for (int64_t seq = 1; seq <= 600; ++seq) (seq % 3 == 0 ? all_messages : all_positions).push_back(seq);
  auto page_after = [](const std::vector<int64_t>& from, int64_t cursor) {
    std::vector<int64_t> page;
    for (int64_t seq : from) {
      if (seq > cursor && page.size() < 16) page.push_back(seq);
    }
    return page;
  };
  std::vector<int64_t> stream;
  int64_t cursor = 0;
  for (int reads = 0; reads < 1000; ++reads) {
    std::vector<int64_t> m = page_after(all_messages, cursor), p = page_after(all_positions, cursor);
    if (m.empty() && p.empty()) break;
    std::vector<int64_t> got = sent(m, m.size() == 16, p, p.size() == 16);
    ASSERT_FALSE(got.empty()) << "no progress after " << cursor;
    stream.insert(stream.end(), got.begin(), got.end());
    cursor = got.back();
  }
  ASSERT_EQ(stream.size(), 600u);
  for (size_t i = 0; i < stream.size(); ++i) EXPECT_EQ(stream[i], static_cast<int64_t>(i + 1));
}

}  // namespace
}  // namespace acomms::service
