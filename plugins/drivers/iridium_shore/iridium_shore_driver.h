#pragma once
// "iridium_shore": the shore's end of the Iridium SBD link, over DirectIP
// (../shared/spec/iridium-sbd.md §9). A shore node with this driver (and
// MAC "none") is an ordinary acommsd: what a vehicle's modem sends arrives
// as received DATA from the vehicle's modem id, and what is queued for that
// id goes out as MTs.
//
// MO (vehicle → shore): the MoServer reads each message the gateway pushes;
// the driver parses it (direct_ip.h), maps the IMEI to a modem id, drops a
// repeat (mo_dedup.h), and hands the payload up as one DATA transmission
// with one frame (a vehicle packs whole DCCL frames into an MO, and DCCL
// messages self-delimit, so the payload is a frame). The gateway's
// connection is answered (MO confirmation, if configured) and closed only
// once what was handed up is durable (DriverCallbacks::after_receipt_durable),
// so that a crash before the commit leaves the MO with the gateway.
//
// MT (shore → vehicle): there are no slots. Every mt_check_interval_s the
// driver asks the queues (on_data_request, one frame of ≤ mt_max_bytes,
// dest = the vehicle) and submits what they give as one MT, with the
// assign-MTMSN flag. One MT is in flight at a time, over all vehicles:
// the queues take any new data request as the end of the last one (what it
// carried and was not acknowledged becomes eligible again), so the next
// request waits for the confirmation. A queued status means the frame is at
// the gateway: it is reported sent and, if the queues asked for it,
// acknowledged as a software ACK from the vehicle would be. Any other
// outcome leaves the frame unacknowledged in the queues, to go again after
// a back-off (the vehicle's MTMSN window and the queues' duplicate window
// drop a second copy if the first did get through).
//
// Bad input (malformed MOs, unknown IEIs, unknown IMEIs, cut-off or slow
// connections, malformed MT confirmations) is logged and counted in
// DriverCounters::bad_input; it never stops the driver.
//
// Core thread only (asserted): sockets on the core's io_context.

#include <asio/io_context.hpp>

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "iridium_shore/iridium_shore_settings.h"
#include "iridium_shore/mo_dedup.h"
#include "iridium_shore/mo_server.h"
#include "iridium_shore/mt_client.h"
#include "link/driver.h"
#include "link/driver_sequence.h"

namespace acomms::drivers {

struct IridiumShoreStats {
  uint64_t mo_handed_up = 0;    // MOs passed on as received DATA
  uint64_t mo_duplicates = 0;   // MOs dropped as already handed up (spec §9.4)
  uint64_t mo_without_payload = 0;  // mailbox checks and failed sessions
  uint64_t mt_queued = 0;       // MTs the gateway confirmed (status ≥ 0)
  uint64_t mt_retry_later = 0;  // no confirmation, or status −5/−6
  uint64_t mt_refused = 0;      // any other negative status
};

class IridiumShoreDriver final : public link::Driver {
 public:
  // Throws std::invalid_argument for a bad iridium_shore config (naming the field).
  IridiumShoreDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, asio::io_context& io_context);
  ~IridiumShoreDriver() override;

  void start(link::DriverCallbacks callbacks) override;
  void stop() override;
  void do_work() override;
  // MTs go out on the driver's own schedule, never in a MAC slot: a
  // transmission the MAC starts is reported failed (use MAC "none").
  void initiate_transmission(const v1::ModemTransmission& transmission) override;
  std::chrono::nanoseconds packet_air_time(int32_t, uint32_t) const override { return {}; }
  std::chrono::nanoseconds ack_time(int32_t) const override { return {}; }
  double sound_speed() const override { return 0; }
  link::DriverCounters counters() const override { return counters_; }
  std::string modem() const override { return "Iridium DirectIP shore endpoint"; }
  bool acks_in_hardware() const override { return true; }

  const IridiumShoreStats& stats() const { return stats_; }
  uint16_t mo_port() const { return server_.local_port(); }

 private:
  struct Vehicle {
    int32_t id = 0;
    std::string imei;
    double next_try_s = 0;   // back-off: no MT before this time
    double backoff_s = 0;    // the last back-off (doubles per failure)
    // The last MT not confirmed: resent with the same client id (MTMSN)
    // when the queues give the same bytes again.
    std::string unconfirmed_payload;
    uint32_t unconfirmed_id = 0;
  };

  void on_mo(std::string message, MoServer::Finish finish);
  void count_bad(const std::string& kind, const std::string& detail);
  // Asks the queues for the next MT, for the vehicles in turn, unless one
  // is in flight.
  void pump();
  void submit(Vehicle& vehicle, v1::ModemTransmission transmission);
  void on_mt_result(Vehicle& vehicle, const v1::ModemTransmission& transmission, uint32_t client_id,
                    const MtSubmitResult& result);
  void back_off(Vehicle& vehicle, double wait_s);
  uint32_t next_client_id();
  double now_s() const { return scheduler_.clock().now_seconds(); }

  IridiumShoreSettings settings_;
  core::Scheduler& scheduler_;
  MoServer server_;
  std::unique_ptr<MtClient> mt_client_;  // null: no mt_gateway
  link::DriverSequence sequence_;        // holds the callbacks between start() and stop()
  MoDedup dedup_;
  std::vector<Vehicle> vehicles_;
  size_t next_vehicle_ = 0;  // round robin over vehicles_
  bool mt_in_flight_ = false;
  double next_check_s_ = 0;
  uint32_t last_client_id_;
  std::set<std::string> unknown_imeis_logged_;  // each logged at warn once, bounded
  link::DriverCounters counters_;
  IridiumShoreStats stats_;
  // Expires with the driver: work waiting for the store checks it first.
  std::shared_ptr<const char> alive_ = std::make_shared<const char>(0);
};

}  // namespace acomms::drivers
