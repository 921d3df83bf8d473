#pragma once
// Consistency checked at sea (README "Consistency across a fleet"): this
// node announces its consistency digest (consistency_digest.h) on each link
// and keeps, per node it hears announce, whether that node agrees.
//
// The problem. A fleet checked before launch still drifts: a vehicle is
// re-flashed on deck with last week's definitions, an operator loads a type
// on one node only, or changes one node's cycle with SetCycle. The first
// sign would be messages that decode wrong.
//
// The decision. Each link carries a 6-byte announce (consistency_announce.h)
// in its first transmission with room for it and then every
// announce_interval_s, as a piggyback (queue/piggyback.h): only in frame
// space no queued message could use, last in its frame. A heard digest
// agrees when it is one of consistency.expected_digest, or, with none
// given, when it equals this node's own digest on the link it was heard
// on. Per (link, node) the last digest, whether it agrees, and since when
// it has not; each (node, digest) that does not agree is logged once, and
// every announce that does not agree is counted. This node's own digest is
// computed afresh whenever it is needed (an announce is due or heard, a
// status is asked for), so definitions loaded at run time and a cycle
// changed with SetCycle are in it at once.
//
// Threads: core thread only (the queues call the piggyback; the service's
// status calls come through the core).

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "acomms/v1/acomms.pb.h"
#include "acomms/v1/config.pb.h"
#include "dccl/codec.h"
#include "mac/mac.h"
#include "queue/piggyback.h"

namespace acomms::node {

inline constexpr double kDefaultAnnounceIntervalS = 600;

struct HeardDigest {
  uint32_t digest = 0;
  bool agrees = false;
  double last_heard = 0;       // clock seconds
  double disagrees_since = 0;  // 0 while it agrees
  uint64_t announces = 0;
};

class ConsistencyWatch final : public queue::Piggyback {
 public:
  // One of the node's links: its name, its MAC config and the MAC (whose
  // cycle is read when the digest is wanted); both outlive the watch.
  struct Link {
    std::string name;
    const v1::MacConfig* config;
    const mac::Mac* mac;
  };

  // Off unless consistency.enabled is true (a bare DCCL decoder at a peer,
  // e.g. a non-acommsd shore, throws at the announce's unknown id).
  // Throws std::invalid_argument naming the consistency field: an
  // announce_id outside 128..32767 or (enabled) the DCCL id of a loaded type, an
  // announce_interval_s below 1, an expected_digest that is not 8 hex
  // digits. Warns when this node's own digest on a link is not expected.
  // `codec` outlives the watch.
  ConsistencyWatch(const v1::ConsistencyConfig& config, const dccl::Codec& codec, std::vector<Link> links);

  bool enabled() const { return enabled_; }
  // This node's digest on link `link` now.
  uint32_t own_digest(int link) const;
  // Whether `digest`, heard on `link`, agrees.
  bool agrees(uint32_t digest, int link) const;

  // Per (link index, node id).
  const std::map<std::pair<int, int32_t>, HeardDigest>& heard() const { return heard_; }
  uint64_t unexpected() const { return unexpected_; }
  uint64_t malformed() const { return malformed_; }

  // GetStatus's consistency fields, and one link's in LinkStatus.
  void fill(v1::Status* status) const;
  void fill_link(int link, v1::LinkStatusResponse* response) const;

  // queue::Piggyback
  uint32_t dccl_id() const override { return announce_id_; }
  std::string take(int link, size_t room, double now) override;
  size_t on_received(std::string_view rest, int32_t src, int link, double now) override;

 private:
  void fill_heard(const std::pair<int, int32_t>& key, const HeardDigest& heard, v1::NodeConsistency* out) const;
  const std::string& link_name(int link) const;

  const dccl::Codec& codec_;
  std::vector<Link> links_;
  bool enabled_;
  double interval_s_;
  uint32_t announce_id_;
  std::set<uint32_t> expected_;
  std::map<int, double> last_sent_;  // link -> when its last announce went
  std::map<std::pair<int, int32_t>, HeardDigest> heard_;
  std::set<std::pair<int32_t, uint32_t>> logged_;  // (node, digest) warned about
  uint64_t unexpected_ = 0;
  uint64_t malformed_ = 0;
};

}  // namespace acomms::node
