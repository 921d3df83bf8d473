#pragma once
// Subscribe's replay reads two tables numbered in one received sequence:
// received messages (the event log) and telemetry's Positions
// (telemetry_position). Each read returns a page in seq order; this is the
// rule that merges two pages into one stream with no gap and no repeat.
//
// The catch: a full page may stop before seqs that the other page already
// holds (messages page ends at 900, positions page holds 850..1200). Only
// seqs up to the lower end of a full page are certain to be complete; the
// rest waits for the next read, which starts after the last seq sent.
//
// Thread-safety: a pure function.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace acomms::service {

struct ReplayPick {
  bool position = false;  // from the positions page (else the messages page)
  size_t index = 0;       // in that page
};

// Both pages in increasing seq; `*_full`: that page held as many as were
// asked for (more may follow it). The picks are in increasing seq.
std::vector<ReplayPick> merge_replay_pages(const std::vector<int64_t>& message_seqs, bool messages_full,
                                           const std::vector<int64_t>& position_seqs, bool positions_full);

}  // namespace acomms::service
