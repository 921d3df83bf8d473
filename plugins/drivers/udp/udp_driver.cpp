#include "udp/udp_driver.h"

#include <spdlog/spdlog.h>

#include <stdexcept>

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
  return std::chrono::duration<double>(scheduler.clock().now().time_since_epoch()).count();
}

}  // namespace

UdpDriver::UdpDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, asio::io_context& io_context)
    : id_(link::own_modem_id(config)),
      max_frame_bytes_(config.udp().max_frame_bytes()),
      max_num_frames_(config.udp().max_num_frames()),
      listen_(config.udp().listen()),
      scheduler_(scheduler),
      transport_(io_context, config.udp().listen(), peers_of(config)) {}

UdpDriver::~UdpDriver() { stop(); }

void UdpDriver::start(link::DriverCallbacks callbacks) {
  stop();
  callbacks_ = std::move(callbacks);
  // Throws DriverError naming the address if it cannot bind.
  transport_.open([this](std::string_view bytes, const std::string& from) { on_datagram(bytes, from); });
  running_ = true;
  spdlog::info("udp modem {}: listening on {}", id_, listen_);
}

void UdpDriver::stop() {
  transport_.close();
  running_ = false;
  callbacks_ = {};
}

void UdpDriver::do_work() {
  // The transport rebinds by itself after a socket failure; a driver that
  // was never started (or stopped) is a caller's error worth a restart.
  if (!running_) throw link::DriverError("udp modem " + std::to_string(id_) + " is not started");
}

void UdpDriver::initiate_transmission(const ModemTransmission& request) {
  if (!running_) throw link::DriverError("udp modem " + std::to_string(id_) + " is not started");
  if (link::is_poll_request(request, id_)) {
    ModemTransmission poll = request;
    poll.clear_frame();
    poll.set_type(ModemTransmission::DATA);
    send(poll, true);
    return;
  }
  if (request.type() != ModemTransmission::DATA) {
    send(request, true);
    return;
  }
  send_data(request);
}

void UdpDriver::send_data(ModemTransmission tx) {
  auto fail = [&](const std::string& error) {
    spdlog::warn("udp modem {}: transmission not sent: {}", id_, error);
    if (callbacks_.on_transmit_result) callbacks_.on_transmit_result(tx, false, error);
  };
  std::string error = link::prepare_data(&tx, id_, max_frame_bytes_, max_num_frames_);
  if (!error.empty()) return fail(error);
  if (callbacks_.on_data_request) callbacks_.on_data_request(&tx);
  error = link::check_frames(tx);
  if (error.empty() && tx.frame_size() == 0) error = "nothing to send: the data request gave no frames";
  if (!error.empty()) return fail(error);
  if (tx.dest() < 0) tx.set_dest(0);  // the queues did not choose: broadcast
  send(tx, true);
}

bool UdpDriver::send(ModemTransmission tx, bool report) {
  tx.set_time(now_seconds(scheduler_));
  std::string bytes = tx.SerializeAsString();
  if (callbacks_.on_raw) callbacks_.on_raw(bytes, true);
  std::string error;
  if (bytes.size() > link::UdpTransport::kMaxDatagram) {
    error = "transmission of " + std::to_string(bytes.size()) + " bytes does not fit a datagram";
  } else {
    error = transport_.send_to_peers(bytes);
  }
  if (error.empty()) ++stats_.sent;
  if (!error.empty()) spdlog::warn("udp modem {}: send failed: {}", id_, error);
  if (report && callbacks_.on_transmit_result) callbacks_.on_transmit_result(tx, error.empty(), error);
  return error.empty();
}

void UdpDriver::on_datagram(std::string_view bytes, const std::string& from) {
  if (callbacks_.on_raw) callbacks_.on_raw(bytes, false);
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
  if (link::is_poll_for(rx, id_)) {
    send_data(link::make_poll_response(rx, id_));
    return;
  }
  if (link::should_report(rx, id_) && callbacks_.on_receive) callbacks_.on_receive(rx);
  if (running_ && link::wants_ack(rx, id_)) send(link::make_ack(rx, id_), /*report=*/false);
}

}  // namespace acomms::drivers
