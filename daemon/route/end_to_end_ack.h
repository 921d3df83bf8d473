#pragma once
// The origin's side of end-to-end acks: which of its messages went wrapped
// to a next hop and still wait to be heard of from afar (route/receipt.h).
//
// The problem. A wrapped message leaves its origin's queue at its first
// hop's ACK (custody passed: the next hop holds it). The end-to-end ack
// (or an expiry report) that comes back later names only its sequence;
// the origin must say which message, of which type, it was about, and an
// operator must see "with next hop 2" until then and "delivered to 3"
// after, even when the origin restarted in between (the ack may come
// hours later, over a satellite).
//
// The decision. Every wrapped send is noted here by sequence (the
// message's journal id mod 2^16), with its type, id, destination and next
// hop; a receipt takes the note. A note is kept until its forget_after
// (sent_at + the message's remaining ttl + the receipt's ttl + a margin:
// no receipt can come later), and at most `max` of them (when full, the
// oldest sent goes first). With a RouteJournal attached every change is
// written through to the store (route_journal.h, migrations/0014) and the
// notes are read back at start: a receipt after a restart, a SIGKILL
// included, is still attached to its message. Without one (tests, nodes
// built without a store) they are in memory only.
//
// Threads: core thread only (a plain class, owned by the Forwarder).

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace acomms::route {

class RouteJournal;  // route_journal.h

struct RoutedSend {
  int64_t message_id = 0;
  std::string type;
  int32_t dest = 0;
  int32_t next_hop = 0;
  double sent_at = 0;
  bool hop_acked = false;  // custody passed to next_hop
  // Clock seconds after which no receipt for it can come: forgotten then.
  double forget_after = 0;
};

class EndToEndAcks {
 public:
  inline static constexpr size_t kDefaultMax = 4096;
  explicit EndToEndAcks(size_t max = kDefaultMax) : max_(max) {}

  // Reads back the notes `journal` holds still at `now` and writes every
  // change through to it from then on. `journal` must outlive this. At
  // start, before any other call. Throws store::StoreError.
  void attach(RouteJournal* journal, double now);

  // `message_id` (sequence = its id mod 2^16) went wrapped (again: replaced).
  // Notes past their forget_after at send.sent_at are forgotten first.
  void sent(RoutedSend send);
  // Its first hop acknowledged it; false when it is not noted.
  bool hop_acked(int64_t message_id);
  // The note of `seq`, or nullptr.
  const RoutedSend* find(uint16_t seq) const;
  // Takes the note of `seq` (a receipt came), or nullopt.
  std::optional<RoutedSend> take(uint16_t seq);
  // Every note, by sequence.
  std::vector<RoutedSend> list() const;

 private:
  void erase(std::map<uint16_t, RoutedSend>::iterator it);

  size_t max_;
  RouteJournal* journal_ = nullptr;
  std::map<uint16_t, RoutedSend> by_seq_;
};

}  // namespace acomms::route
