#pragma once
// The Iridium SBD gateway (the "GSS" of ../shared/spec/iridium-sbd.md) as a
// fake 9603 sees it: where a session's MO goes and where its MT comes from.
//
// Two fakes meet here. The fake modem (fake_sbd_modem) runs the AT side of a
// session and calls this interface; a gateway implements it: in memory for
// the vehicle driver's own tests (InMemorySbdGateway below), or the fake
// DirectIP gateway, which pushes each MO to a shore endpoint over DirectIP
// and queues the MTs a shore endpoint submits (spec §9). Keeping the seam
// this small is what lets a reader check each fake against the spec alone.
//
// Thread-safety: implementations are called from the fake modem's thread and
// from their own; every member must be safe to call from any thread.

#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace acomms::fake_iridium {

struct MtMessage {
  uint16_t mtmsn = 0;   // 1..65535, fixed when the MT was queued (spec §9.4)
  std::string payload;  // at most 270 bytes (spec §6.1)
};

class SbdGateway {
 public:
  virtual ~SbdGateway() = default;
  // A session delivered this MO to the gateway (the modem has not yet been
  // told: a fault may still lose the answer, spec §11). An empty payload is
  // a mailbox check and is not passed on.
  virtual void mo_received(const std::string& imei, uint16_t momsn, const std::string& payload) = 0;
  // The oldest MT waiting for `imei`, taken off its queue; nullopt if none.
  virtual std::optional<MtMessage> take_mt(const std::string& imei) = 0;
  // How many MTs still wait for `imei`.
  virtual int mt_queued(const std::string& imei) const = 0;
};

// A gateway that keeps everything in memory: what the vehicle sent, and MTs
// a test queues for it.
class InMemorySbdGateway : public SbdGateway {
 public:
  struct Mo {
    std::string imei;
    uint16_t momsn = 0;
    std::string payload;
  };

  void mo_received(const std::string& imei, uint16_t momsn, const std::string& payload) override {
    std::lock_guard lock(mutex_);
    mo_.push_back({imei, momsn, payload});
  }
  std::optional<MtMessage> take_mt(const std::string& imei) override {
    std::lock_guard lock(mutex_);
    auto& queue = mt_[imei];
    if (queue.empty()) return std::nullopt;
    MtMessage m = std::move(queue.front());
    queue.pop_front();
    return m;
  }
  int mt_queued(const std::string& imei) const override {
    std::lock_guard lock(mutex_);
    auto it = mt_.find(imei);
    return it == mt_.end() ? 0 : static_cast<int>(it->second.size());
  }

  // Queues an MT; its MTMSN counts 1..65535 and wraps to 1 (spec §9.4).
  uint16_t queue_mt(const std::string& imei, std::string payload) {
    std::lock_guard lock(mutex_);
    next_mtmsn_ = next_mtmsn_ == 65535 ? 1 : next_mtmsn_ + 1;
    mt_[imei].push_back({next_mtmsn_, std::move(payload)});
    return next_mtmsn_;
  }
  std::vector<Mo> mo() const {
    std::lock_guard lock(mutex_);
    return mo_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<Mo> mo_;
  std::map<std::string, std::deque<MtMessage>> mt_;
  uint16_t next_mtmsn_ = 0;
};

}  // namespace acomms::fake_iridium
