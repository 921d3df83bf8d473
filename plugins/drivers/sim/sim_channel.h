#pragma once
// The shared water of simulated modems in one process, typically all on one
// SimulatedScheduler: a test or `acommsctl sim` creates one SimChannel and
// hands it to every SimDriver. A transmission is passed to every other
// connected node at once; each works out when (and whether) it hears it.
// Deterministic: with the same seed and the same calls, the same outcome.

#include <cstdint>
#include <map>
#include <memory>

#include "sim/sim_medium.h"

namespace acomms::drivers {

class SimChannel : public std::enable_shared_from_this<SimChannel> {
 public:
  // `seed` seeds each node's loss draws (mixed with its modem id) unless
  // the node's config has its own seed.
  static std::shared_ptr<SimChannel> create(uint32_t seed = 1);

  uint32_t seed() const { return seed_; }
  // A medium for one node; it joins the channel when opened.
  std::unique_ptr<SimMedium> connect();
  // Nodes currently open on the channel.
  size_t size() const { return listeners_.size(); }

 private:
  explicit SimChannel(uint32_t seed) : seed_(seed) {}
  friend class ChannelPort;
  uint64_t join(SimMedium::Listener listener);
  void leave(uint64_t port);
  void broadcast(uint64_t from_port, const SimEnvelope& envelope);

  uint32_t seed_;
  uint64_t next_port_ = 1;
  std::map<uint64_t, SimMedium::Listener> listeners_;  // ordered: deterministic delivery
};

}  // namespace acomms::drivers
