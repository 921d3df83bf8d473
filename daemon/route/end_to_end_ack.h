#pragma once
// The origin's side of end-to-end acks: which of its messages went wrapped
// to a next hop and still wait to be heard of from afar (route/receipt.h).
//
// The problem. A wrapped message leaves its origin's queue at its first
// hop's ACK (custody passed: the next hop holds it). The end-to-end ack
// (or an expiry report) that comes back later names only its sequence;
// the origin must say which message, of which type, it was about, and an
// operator must see "with next hop 2" until then and "delivered to 3"
// after.
//
// The decision. Every wrapped send is noted here by sequence (the
// message's journal id mod 2^16), with its type, id, destination and next
// hop; a receipt takes the note. Bounded (the oldest note goes first) and
// in memory only: after a restart of the origin, a receipt for a message
// sent before it is logged, not attached to its message.
//
// Threads: core thread only (a plain class, owned by the Forwarder).

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace acomms::route {

struct RoutedSend {
  int64_t message_id = 0;
  std::string type;
  int32_t dest = 0;
  int32_t next_hop = 0;
  double sent_at = 0;
  bool hop_acked = false;  // custody passed to next_hop
};

class EndToEndAcks {
 public:
  inline static constexpr size_t kDefaultMax = 4096;
  explicit EndToEndAcks(size_t max = kDefaultMax) : max_(max) {}

  // `message_id` (sequence = its id mod 2^16) went wrapped (again: replaced).
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
  size_t max_;
  std::map<uint16_t, RoutedSend> by_seq_;
};

}  // namespace acomms::route
