#pragma once
// What a gateway remembers of routing across a restart: the origin's notes
// of routed messages that await their end-to-end ack (end_to_end_ack.h;
// table route_awaiting, migrations/0014) and the routes learned from
// traffic (route_table.h; table route_learned, migrations/0015).
//
// The problem. Both lived in memory only. An origin restarted between a
// message's hop ack and its end-to-end ack logged the ack as "a message
// this node no longer knows" and `events` never showed the final ack; a
// buoy restarted (SIGKILLed, its battery swapped) forgot which vehicles it
// hears, and the shore's commands waited for a vehicle to speak again.
//
// The decision. Written through the store's GroupCommitWriter (post: the
// core never waits for the disk; a failed write is logged by the writer
// and only costs the memory after a restart, never a message), read back
// once at start. Each table is keyed so that it is bounded by itself (one
// row per sequence, one per destination); notes are pruned by their own
// forget_after as they are read. The writer's FIFO keeps a note's write
// before the queue event that follows it (the hop ack's), so after a crash
// a message that left its queue has its note.
//
// Threads: the writes post to the writer from the caller's thread (the
// core); the loads wait for the writer and run at start, before the core.

#include <cstdint>
#include <string>
#include <vector>

#include "route/end_to_end_ack.h"
#include "route/route_table.h"
#include "store/group_commit_writer.h"

namespace acomms::route {

// A learned route as stored.
struct StoredRoute {
  int32_t dest = 0;
  NextHop next;
  double last_confirmed = 0;
};

class RouteJournal {
 public:
  // `writer` writes a store migrated to 0015 or later and outlives this.
  explicit RouteJournal(store::GroupCommitWriter& writer) : writer_(writer) {}

  // The note of `send` (replacing its sequence's).
  void save_awaiting(const RoutedSend& send);
  // Forgets the note of sequence `seq`.
  void erase_awaiting(uint16_t seq);
  // The notes still to be kept at `now` (forget_after >= now), oldest sent
  // first; those past it are deleted. Throws store::StoreError.
  std::vector<RoutedSend> load_awaiting(double now);

  // Learned route to `dest` now.
  void save_learned(int32_t dest, const NextHop& next, double last_confirmed);
  // Every learned route stored, by destination; rows that do not read as
  // one (a source this build does not know, an id out of range) are
  // skipped with a warning. Throws store::StoreError.
  std::vector<StoredRoute> load_learned();

 private:
  store::GroupCommitWriter& writer_;
};

}  // namespace acomms::route
