#pragma once
// Following routed messages hop by hop through real daemons, for the
// network's figures (messages, hops, acks, delay per hop).
//
// The problem. A message's identity across hops is (origin, sequence) in
// its envelope; a relay journals it under an id of its own and its events
// name only that id. ListQueued shows a custody message's envelope head
// (origin, destination, sequence, hops) while the relay holds it, and the
// relay's event log keeps when it took custody ("queued") and when the
// next hop acknowledged it ("acked") under its own id, across restarts.
//
// The decision. CustodyWatch polls every relay's ListQueued (every 50 ms,
// on its own thread) and keeps the first sighting of each custody message:
// that ties the relay's id to the envelope's identity. A custody message
// held for less than one poll is not seen; its message's hops are then not
// traced (counted, never guessed). The times come from the event logs
// afterwards, not from the polls.
//
// Thread-safety: CustodyWatch's members may be called from any thread; the
// free functions are thread-compatible (they only call the API).

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "acomms/v1/acomms.grpc.pb.h"

namespace acomms::testing {

// A custody message as a relay listed it.
struct CustodySighting {
  int node = 0;          // the relay
  int64_t local_id = 0;  // its message id there
  int origin = 0;
  int destination = 0;
  int seq = 0;  // the envelope's sequence: the origin's message id mod 65536
  int hops = 0;
};

class CustodyWatch {
 public:
  // `relays`: node id -> API socket.
  explicit CustodyWatch(std::map<int, std::string> relays);
  ~CustodyWatch();
  CustodyWatch(const CustodyWatch&) = delete;
  CustodyWatch& operator=(const CustodyWatch&) = delete;

  std::vector<CustodySighting> sightings() const;

 private:
  void poll_once();

  std::map<int, std::string> relays_;
  mutable std::mutex mutex_;
  std::map<std::pair<int, int64_t>, CustodySighting> seen_;
  std::atomic<bool> running_{true};
  std::thread thread_;
};

// Every event in `socket`'s log of these kinds (empty: all), oldest first.
std::vector<v1::Event> node_events(const std::string& socket, const std::vector<std::string>& kinds = {});

// One message's history at a node (Events by message id): its hop acks
// ("acked") and its end-to-end ack ("delivered").
std::vector<v1::Event> message_history(const std::string& socket, int64_t message_id);

// A message the test sent, and what became of it.
struct TracedMessage {
  std::string what;  // "Command", "Status", ...
  int origin = 0;
  int destination = 0;
  int64_t origin_id = 0;         // SubmitResponse.message_id at the origin
  std::vector<int> path;         // the nodes it must pass, origin first, destination last
  double delivered_at = 0;       // receive_time at the destination (0: not delivered)
};

struct HopDelay {
  int n = 0;
  double sum_s = 0;
  double max_s = 0;
};

// The figures of a run: per hop (from -> to) delays, hop counts, acks.
struct NetworkFigures {
  int messages = 0;
  int delivered = 0;
  int traced = 0;               // messages whose every hop was seen
  int hops = 0;                 // hops taken by the traced messages
  uint64_t sent_events = 0;     // "sent" events on every node (each try of each hop)
  uint64_t retries = 0;         // "retry" events: a hop not acknowledged in time
  uint64_t hop_acks = 0;        // "acked" events on every node (an ACK from the next hop)
  uint64_t end_to_end_acks = 0; // "delivered" events at the origins (the destination's receipt came back)
  std::map<std::pair<int, int>, HopDelay> per_hop;
  // Per relay: from taking custody to the first send of the message on.
  std::map<int, HopDelay> relay_wait;
  std::map<int, int64_t> relay_worst_id;  // the relay's id of its longest wait
  std::vector<double> end_to_end_s;

  void print(std::ostream& out, const std::map<int, std::string>& names) const;
};

// `events`: node -> node_events(that node). Times: the origin's "queued",
// each relay's "queued" of its custody copy, the destination's receive_time.
NetworkFigures network_figures(const std::vector<TracedMessage>& messages,
                               const std::vector<CustodySighting>& sightings,
                               const std::map<int, std::vector<v1::Event>>& events);

}  // namespace acomms::testing
