#pragma once
// Connects one node's driver, MAC and queues: the MAC's slots become
// transmissions, the driver's data requests are filled by the queues,
// received frames are split into messages for the subscribers, and ACKs
// clear what they acknowledge. Runs on the core thread.

#include <cstdint>
#include <functional>
#include <map>
#include <string_view>
#include <vector>

#include "acomms/v1/modem_transmission.pb.h"
#include "link/driver.h"
#include "mac/mac.h"
#include "queue/queue_manager.h"

namespace acomms::link {

struct LinkStats {
  uint64_t transmissions_sent = 0;
  uint64_t transmissions_failed = 0;
  uint64_t data_received = 0;      // DATA transmissions heard (any destination)
  uint64_t acks_received = 0;      // ACKs for this node
  uint64_t messages_delivered = 0;
  uint64_t receptions_with_figures = 0;  // DATA that carried the modem's ReceptionFigures
  uint64_t bad_frames_received = 0;      // frames those packets lost (figures.bad_frames)
};

class LinkController {
 public:
  // Called for every received message meant for this node.
  using Deliver = std::function<void(queue::ReceivedMessage message, const v1::ModemTransmission& from)>;

  // All references must outlive the controller.
  LinkController(int32_t own_id, queue::QueueManager& queues, mac::Mac& mac, Driver& driver, Deliver deliver);

  // Starts the driver, then the MAC. Throws what the driver's start throws.
  void start();
  // Stops the MAC, then the driver.
  void stop();

  const LinkStats& stats() const { return stats_; }
  // Every chunk of bytes to (outgoing) and from the device, as the driver
  // reports it (the raw link log). Set before start().
  void set_raw_tap(std::function<void(std::string_view bytes, bool outgoing)> tap) { raw_tap_ = std::move(tap); }

 private:
  void on_data_request(v1::ModemTransmission* transmission);
  void on_receive(const v1::ModemTransmission& transmission);
  void on_transmit_result(const v1::ModemTransmission& transmission, bool ok, const std::string& error);

  int32_t own_id_;
  queue::QueueManager& queues_;
  mac::Mac& mac_;
  Driver& driver_;
  Deliver deliver_;
  // Queue frame ids of the last DATA transmission to each destination, by
  // frame index: an ACK names indices, the queues know frame ids.
  std::map<int32_t, std::vector<uint64_t>> awaiting_ack_;
  LinkStats stats_;
  std::function<void(std::string_view, bool)> raw_tap_;
};

}  // namespace acomms::link
