#include "udp/udp_driver.h"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "core/core_thread.h"
#include "link/transmission_rules.h"

namespace acomms::drivers {

using v1::ModemTransmission;

namespace {

std::vector<std::string> peers_of(const v1::DriverConfig& config) {
  if (config.udp().listen().empty()) {
    throw std::invalid_argument("driver.udp.listen is empty: the udp driver needs a host:port to listen on");
  }
  return {config.udp().peers().begin(), config.udp().peers().end()};
}

double now_seconds(const core::Scheduler& scheduler) {
  return scheduler.clock().now_seconds();
}

}  // namespace

UdpDriver::UdpDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, asio::io_context& io_context)
    : id_(link::own_modem_id(config)),
      listen_(config.udp().listen()),
      scheduler_(scheduler),
      transport_(io_context, config.udp().listen(), peers_of(config)),
      sequence_({"udp modem " + std::to_string(id_), id_, config.udp().max_frame_bytes(),
                 config.udp().max_num_frames()},
                {[this](const ModemTransmission& tx, bool report) { return send(tx, report); }}) {}

UdpDriver::~UdpDriver() { stop(); }

void UdpDriver::start(link::DriverCallbacks callbacks) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  sequence_.start(std::move(callbacks));
  try {
    // Throws DriverError naming the address if it cannot bind.
    transport_.open([this](std::string_view bytes, const std::string& from) { on_datagram(bytes, from); });
  } catch (...) {
    sequence_.stop();
    throw;
  }
  spdlog::info("udp modem {}: listening on {}", id_, listen_);
}

void UdpDriver::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  transport_.close();
  sequence_.stop();
}

void UdpDriver::do_work() {
  // The transport rebinds by itself after a socket failure; a driver that
  // was never started (or stopped) is a caller's error worth a restart.
  ACOMMS_ASSERT_CORE_THREAD();
  sequence_.check_running();
}

void UdpDriver::initiate_transmission(const ModemTransmission& request) { sequence_.transmit(request); }

std::string UdpDriver::send(ModemTransmission tx, bool report) {
  ACOMMS_ASSERT_CORE_THREAD();
  tx.set_time(now_seconds(scheduler_));
  std::string bytes = tx.SerializeAsString();
  if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(bytes, true);
  std::string error;
  if (bytes.size() > link::UdpTransport::kMaxDatagram) {
    error = "transmission of " + std::to_string(bytes.size()) + " bytes does not fit a datagram";
  } else {
    error = transport_.send_to_peers(bytes);
  }
  if (!error.empty()) {
    // A reported transmission's failure is logged by the sequence.
    if (!report) spdlog::warn("udp modem {}: send failed: {}", id_, error);
    return error;
  }
  ++stats_.sent;
  if (report) sequence_.report(tx, true, "");
  return "";
}

void UdpDriver::on_datagram(std::string_view bytes, const std::string& from) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(bytes, false);
  ModemTransmission rx;
  // A transmission must parse and name its sender; anything else that
  // reaches the port (a port scan, another program) is dropped.
  if (!rx.ParseFromArray(bytes.data(), static_cast<int>(bytes.size())) || !rx.has_src() || rx.src() < 0) {
    ++stats_.garbage;
    spdlog::warn("udp modem {}: dropped a malformed datagram of {} bytes from {}", id_, bytes.size(), from);
    return;
  }
  ++stats_.received;
  rx.set_time(now_seconds(scheduler_));
  // No turnaround on an IP link: polls and ACKs are answered at once.
  sequence_.on_received(rx);
}

}  // namespace acomms::drivers
