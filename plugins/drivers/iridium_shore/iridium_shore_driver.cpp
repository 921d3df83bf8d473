#include "iridium_shore/iridium_shore_driver.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "core/core_thread.h"
#include "iridium_shore/direct_ip.h"

namespace acomms::drivers {

using v1::ModemTransmission;

namespace {

constexpr size_t kUnknownImeisLogged = 256;

std::string label_of(const IridiumShoreSettings& settings) {
  return "iridium shore " + std::to_string(settings.own_id);
}

}  // namespace

IridiumShoreDriver::IridiumShoreDriver(const v1::DriverConfig& config, core::Scheduler& scheduler,
                                       asio::io_context& io_context)
    : settings_(IridiumShoreSettings::from_config(config)),
      scheduler_(scheduler),
      server_(io_context, settings_.mo_listen, settings_.mo_listen_text, settings_.max_mo_connections,
              settings_.mo_read_timeout),
      sequence_({label_of(settings_), settings_.own_id, settings_.mt_max_bytes, 1, /*software_acks=*/false},
                {[this](const ModemTransmission&, bool) {
                  return std::string("iridium_shore sends MTs on its own schedule, not in MAC slots "
                                     "(configure mac { name: \"none\" })");
                }}),
      dedup_(settings_.mo_dedup_window_s, settings_.mo_dedup_capacity) {
  if (!settings_.mt_gateway.empty()) {
    mt_client_ = std::make_unique<MtClient>(io_context, settings_.mt_gateway_address, settings_.mt_gateway,
                                            settings_.mt_connect_timeout, settings_.mt_confirmation_timeout);
  }
  for (const auto& [id, imei] : settings_.imei_by_modem_id) {
    Vehicle vehicle;
    vehicle.id = id;
    vehicle.imei = imei;
    vehicles_.push_back(std::move(vehicle));
  }
  // MTMSNs (our client ids, spec §9.4) start from the clock, not from 1:
  // a vehicle drops an MTMSN it saw among its last 64, so numbering must
  // not begin again at each start. MTs are far fewer than one per second,
  // so the clock runs ahead of the last number used before a restart.
  last_client_id_ = static_cast<uint32_t>(static_cast<uint64_t>(now_s()) % 65535);
}

IridiumShoreDriver::~IridiumShoreDriver() { stop(); }

void IridiumShoreDriver::start(link::DriverCallbacks callbacks) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  sequence_.start(std::move(callbacks));
  try {
    server_.open([this](std::string message, MoServer::Finish finish) { on_mo(std::move(message), std::move(finish)); },
                 [this](const std::string& kind, const std::string& detail) { count_bad(kind, detail); });
  } catch (...) {
    sequence_.stop();
    throw;
  }
  next_check_s_ = 0;
  spdlog::info("{}: MO server on {} (port {}), MT gateway {}, {} modem(s)", label_of(settings_), settings_.mo_listen_text,
               server_.local_port(), settings_.mt_gateway.empty() ? "none" : settings_.mt_gateway, vehicles_.size());
}

void IridiumShoreDriver::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  server_.close();
  if (mt_client_) mt_client_->close();
  // An MT in flight is abandoned: its frame stays unacknowledged and goes
  // again after a restart.
  mt_in_flight_ = false;
  sequence_.stop();
}

void IridiumShoreDriver::do_work() {
  ACOMMS_ASSERT_CORE_THREAD();
  sequence_.check_running();
  if (now_s() < next_check_s_) return;
  next_check_s_ = now_s() + settings_.mt_check_interval_s;
  pump();
}

void IridiumShoreDriver::initiate_transmission(const ModemTransmission& transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  sequence_.check_running();
  sequence_.report(transmission, false,
                   "iridium_shore sends MTs on its own schedule, not in MAC slots (configure mac { name: \"none\" })");
}

void IridiumShoreDriver::count_bad(const std::string& kind, const std::string& detail) {
  ++counters_.bad_input[kind];
  spdlog::warn("{}: {}: {}", label_of(settings_), kind, detail);
}

void IridiumShoreDriver::on_mo(std::string message, MoServer::Finish finish) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!sequence_.running()) return;
  const auto& callbacks = sequence_.callbacks();
  if (callbacks.on_raw) callbacks.on_raw(message, false);
  std::string error;
  std::optional<directip::MoMessage> mo = directip::parse_mo(message, &error);
  if (!mo) {
    count_bad("MO refused", error);
    return finish("");  // nothing to confirm: the gateway may try again, to the same end
  }
  if (mo->unknown_ies > 0) counters_.bad_input["MO unknown IE"] += mo->unknown_ies;
  if (mo->unusable_locations > 0) counters_.bad_input["MO unusable location"] += mo->unusable_locations;
  const std::string confirmation = settings_.mo_confirmation ? directip::build_mo_confirmation(true) : "";
  const directip::MoHeader& header = mo->header;
  auto vehicle = settings_.modem_id_by_imei.find(header.imei);
  if (vehicle == settings_.modem_id_by_imei.end()) {
    ++counters_.bad_input["MO from an unknown IMEI"];
    if (unknown_imeis_logged_.size() < kUnknownImeisLogged && unknown_imeis_logged_.insert(header.imei).second) {
      spdlog::warn("{}: dropped an MO from IMEI {}, which is not in driver.iridium_shore.modems (MOMSN {})",
                   label_of(settings_), header.imei, header.momsn);
    }
    // Taken (and confirmed) all the same: refusing it would only make the
    // gateway bring it back for 12 hours.
    return finish(confirmation);
  }
  if (!directip::mo_session_succeeded(header.session_status) || mo->payload.empty()) {
    ++stats_.mo_without_payload;
    spdlog::debug("{}: MO from modem {} without payload (session status {}, MOMSN {})", label_of(settings_),
                  vehicle->second, header.session_status, header.momsn);
    return finish(confirmation);
  }
  const double now = now_s();
  const bool duplicate = dedup_.contains(header.imei, header.momsn, mo->payload, now);
  if (duplicate) {
    ++stats_.mo_duplicates;
    spdlog::info("{}: MO from modem {} (IMEI {}, MOMSN {}) was handed up before: dropped", label_of(settings_),
                 vehicle->second, header.imei, header.momsn);
  } else {
    ModemTransmission received;
    received.set_src(vehicle->second);
    received.set_dest(settings_.own_id);
    received.set_type(ModemTransmission::DATA);
    received.set_ack_requested(false);  // the gateway's session result is the vehicle's ACK
    received.set_time(now);
    received.add_frame(mo->payload);
    received.set_link_quality("iridium momsn " + std::to_string(header.momsn) + " cdr " +
                              std::to_string(header.cdr_reference) + " session_time " +
                              std::to_string(header.session_time));
    ++stats_.mo_handed_up;
    if (callbacks.on_receive) callbacks.on_receive(received);
  }
  // Answered only once what was handed up (this MO, or the first copy of
  // a duplicate) is durable: until then a crash must leave it with the
  // gateway (spec §9.5).
  auto answer = [this, alive = std::weak_ptr<const char>(alive_), finish, confirmation, duplicate,
                 imei = header.imei, momsn = header.momsn, payload = std::move(mo->payload), now] {
    if (alive.expired()) return;
    if (!duplicate) dedup_.remember(imei, momsn, payload, now);
    finish(confirmation);
  };
  if (sequence_.running() && sequence_.callbacks().after_receipt_durable) {
    sequence_.callbacks().after_receipt_durable(std::move(answer));
  } else {
    answer();
  }
}

void IridiumShoreDriver::pump() {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!mt_client_ || mt_in_flight_ || !sequence_.running() || vehicles_.empty()) return;
  const double now = now_s();
  for (size_t n = 0; n < vehicles_.size(); ++n) {
    Vehicle& vehicle = vehicles_[(next_vehicle_ + n) % vehicles_.size()];
    if (now < vehicle.next_try_s) continue;
    ModemTransmission transmission;
    transmission.set_dest(vehicle.id);
    transmission.set_ack_requested(true);
    if (!sequence_.request_frames(&transmission).empty()) continue;  // nothing for this vehicle
    // With nothing queued the link still fills a slot with one empty frame
    // (link_controller.cpp); a satellite message is paid for: none is sent.
    if (transmission.frame(0).empty()) continue;
    next_vehicle_ = (next_vehicle_ + n + 1) % vehicles_.size();
    submit(vehicle, std::move(transmission));
    return;
  }
}

uint32_t IridiumShoreDriver::next_client_id() {
  last_client_id_ = last_client_id_ >= 65535 ? 1 : last_client_id_ + 1;  // 1..65535 (spec §9.4)
  return last_client_id_;
}

void IridiumShoreDriver::submit(Vehicle& vehicle, ModemTransmission transmission) {
  directip::MtSubmission mt;
  mt.imei = vehicle.imei;
  mt.payload = transmission.frame(0);
  mt.flags = directip::kAssignMtmsn;
  mt.client_id = mt.payload == vehicle.unconfirmed_payload ? vehicle.unconfirmed_id : next_client_id();
  vehicle.unconfirmed_payload = mt.payload;
  vehicle.unconfirmed_id = mt.client_id;
  std::string error;
  std::string bytes = directip::build_mt(mt, &error);
  transmission.set_time(now_s());
  if (bytes.empty()) {
    // Cannot happen with checked settings (IMEI, mt_max_bytes ≤ 270).
    sequence_.report(transmission, false, "MT not built: " + error);
    return back_off(vehicle, settings_.mt_refused_wait_s);
  }
  if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(bytes, true);
  mt_in_flight_ = true;
  const size_t index = static_cast<size_t>(&vehicle - vehicles_.data());
  mt_client_->submit(std::move(bytes), [this, index, transmission, client_id = mt.client_id](MtSubmitResult result) {
    mt_in_flight_ = false;
    if (!sequence_.running()) return;
    on_mt_result(vehicles_[index], transmission, client_id, result);
    pump();  // the next MT, if any, at once
  });
}

void IridiumShoreDriver::on_mt_result(Vehicle& vehicle, const ModemTransmission& transmission, uint32_t client_id,
                                      const MtSubmitResult& result) {
  ACOMMS_ASSERT_CORE_THREAD();
  const std::string label = label_of(settings_);
  if (!result.confirmation) {
    if (result.malformed) ++counters_.bad_input["MT confirmation refused"];
    ++stats_.mt_retry_later;
    sequence_.report(transmission, false, "MT to modem " + std::to_string(vehicle.id) + " not confirmed: " + result.error);
    return back_off(vehicle, vehicle.backoff_s == 0 ? settings_.mt_retry_min_s
                                                    : std::min(settings_.mt_retry_max_s, vehicle.backoff_s * 2));
  }
  const directip::MtConfirmation& c = *result.confirmation;
  if (c.client_id != client_id || c.imei != vehicle.imei) {
    spdlog::warn("{}: MT confirmation names client id {} and IMEI {}, we sent {} to {}", label, c.client_id, c.imei,
                 client_id, vehicle.imei);
  }
  switch (directip::mt_outcome(c.status)) {
    case directip::MtOutcome::kQueued: {
      ++stats_.mt_queued;
      vehicle.backoff_s = 0;
      vehicle.unconfirmed_payload.clear();
      spdlog::info("{}: MT of {} bytes for modem {} queued at the gateway: MTMSN {}, status {}", label,
                   transmission.frame(0).size(), vehicle.id, client_id, directip::mt_status_text(c.status));
      sequence_.report(transmission, true, "");
      if (!transmission.ack_requested() || !sequence_.callbacks().on_receive) return;
      // The frame is at the gateway, which keeps it for the vehicle for 5
      // days: for the queues that is the end of the message, as a software
      // ACK from the vehicle would be on a link with no gateway between.
      ModemTransmission ack;
      ack.set_type(ModemTransmission::ACK);
      ack.set_src(vehicle.id);
      ack.set_dest(settings_.own_id);
      ack.set_time(now_s());
      ack.add_acked_frame(0);
      sequence_.callbacks().on_receive(ack);
      return;
    }
    case directip::MtOutcome::kRetryLater:
      ++stats_.mt_retry_later;
      sequence_.report(transmission, false, "gateway cannot take the MT for modem " + std::to_string(vehicle.id) +
                                                " now: " + directip::mt_status_text(c.status));
      return back_off(vehicle, vehicle.backoff_s == 0 ? settings_.mt_retry_min_s
                                                      : std::min(settings_.mt_retry_max_s, vehicle.backoff_s * 2));
    case directip::MtOutcome::kRefused:
      ++stats_.mt_refused;
      vehicle.unconfirmed_payload.clear();  // the gateway has not kept it
      spdlog::error("{}: the gateway refused the MT for modem {} (IMEI {}): {}; its MTs wait {} s (check the "
                    "IMEI's provisioning and the gateway's MT filter)",
                    label, vehicle.id, vehicle.imei, directip::mt_status_text(c.status), settings_.mt_refused_wait_s);
      sequence_.report(transmission, false, "MT refused: " + directip::mt_status_text(c.status));
      return back_off(vehicle, settings_.mt_refused_wait_s);
  }
}

void IridiumShoreDriver::back_off(Vehicle& vehicle, double wait_s) {
  vehicle.backoff_s = wait_s;
  vehicle.next_try_s = now_s() + wait_s;
}

}  // namespace acomms::drivers
