#include "sim/sim_channel.h"

#include <vector>

namespace acomms::drivers {

// One node's connection to the channel.
class ChannelPort final : public SimMedium {
 public:
  explicit ChannelPort(std::shared_ptr<SimChannel> channel) : channel_(std::move(channel)) {}
  ~ChannelPort() override { close(); }

  void open(Listener listener, RawListener) override {
    close();
    port_ = channel_->join(std::move(listener));
  }
  void close() override {
    if (port_ != 0) channel_->leave(port_);
    port_ = 0;
  }
  std::string send(const SimEnvelope& envelope) override {
    if (port_ == 0) return "not connected to the channel";
    channel_->broadcast(port_, envelope);
    return "";
  }

 private:
  std::shared_ptr<SimChannel> channel_;
  uint64_t port_ = 0;
};

std::shared_ptr<SimChannel> SimChannel::create(uint32_t seed) {
  return std::shared_ptr<SimChannel>(new SimChannel(seed));
}

std::unique_ptr<SimMedium> SimChannel::connect() { return std::make_unique<ChannelPort>(shared_from_this()); }

uint64_t SimChannel::join(SimMedium::Listener listener) {
  uint64_t port = next_port_++;
  listeners_.emplace(port, std::move(listener));
  return port;
}

void SimChannel::leave(uint64_t port) { listeners_.erase(port); }

void SimChannel::broadcast(uint64_t from_port, const SimEnvelope& envelope) {
  // A copy: a listener may make its node leave (or join) the channel.
  std::vector<std::pair<uint64_t, SimMedium::Listener>> listeners(listeners_.begin(), listeners_.end());
  for (auto& [port, listener] : listeners) {
    if (port != from_port && listeners_.count(port)) listener(envelope);
  }
}

}  // namespace acomms::drivers
