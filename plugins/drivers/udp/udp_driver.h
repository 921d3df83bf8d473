#pragma once
// "udp": a link where each datagram carries one serialized
// ModemTransmission to every configured peer. For bench tests of several
// daemons on one network, and for links that really are IP (a radio or a
// tether), with the same frame limits as the acoustic modem so that the
// queues build the same frames.
//
// It behaves like a modem for the MAC and the queues (driver.h, run by
// link::DriverSequence): frame limits from udp.max_frame_bytes / udp.max_num_frames or the Micro-Modem
// table for the rate, software ACKs for DATA to us with ack_requested, and
// polls: a request whose src is another node is sent as an empty DATA with
// that node's src, and a node hearing DATA with its own id as src answers
// with its data. There is no air time: everything goes out at once and
// on_transmit_result is reported right after sending, so the slot budget
// (link/slot_budget.h) sees no air time, turnaround or travel and never
// takes frames away. Datagrams that do not
// parse are counted and logged, never fatal.

#include <asio/io_context.hpp>

#include <chrono>
#include <cstdint>
#include <memory>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "link/driver.h"
#include "link/driver_sequence.h"
#include "link/udp_transport.h"

namespace acomms::drivers {

struct UdpDriverStats {
  uint64_t sent = 0;      // datagrams sent (to all peers)
  uint64_t received = 0;  // well-formed transmissions received
  uint64_t garbage = 0;   // datagrams dropped as malformed
};

class UdpDriver final : public link::Driver {
 public:
  // Throws std::invalid_argument for a bad udp config (naming the field).
  UdpDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, asio::io_context& io_context);
  ~UdpDriver() override;

  void start(link::DriverCallbacks callbacks) override;
  void stop() override;
  void do_work() override;
  void initiate_transmission(const v1::ModemTransmission& transmission) override;
  std::chrono::nanoseconds packet_air_time(int32_t, uint32_t) const override { return {}; }
  std::chrono::nanoseconds ack_time(int32_t) const override { return {}; }
  double sound_speed() const override { return 0; }

  int32_t modem_id() const { return id_; }
  const UdpDriverStats& stats() const { return stats_; }
  uint16_t listen_port() const { return transport_.local_port(); }

 private:
  void on_datagram(std::string_view bytes, const std::string& from);
  // The sequence's Medium::send: one datagram to every peer, reported at
  // once (when `report`); "" or why it could not go out.
  std::string send(v1::ModemTransmission transmission, bool report);

  int32_t id_;
  std::string listen_;
  core::Scheduler& scheduler_;
  link::UdpTransport transport_;
  link::DriverSequence sequence_;  // holds the callbacks between start() and stop()
  UdpDriverStats stats_;
};

}  // namespace acomms::drivers
