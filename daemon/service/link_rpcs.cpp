// LinkStatus and SetCycle: the driver and the MAC.
#include "mac/mac_factory.h"
#include "service/acomms_service.h"

namespace acomms::service {
namespace {

v1::MacSlot to_proto(const mac::Slot& slot) {
  v1::MacSlot out;
  out.set_src(slot.src);
  if (slot.dest >= 0) out.set_dest(slot.dest);
  out.set_rate(slot.rate);
  out.set_seconds(slot.seconds);
  return out;
}

}  // namespace

grpc::Status AcommsService::LinkStatus(grpc::ServerContext* context, const v1::LinkStatusRequest*,
                                       v1::LinkStatusResponse* response) {
  if (grpc::Status denied = allowed(*context, "LinkStatus"); !denied.ok()) return denied;
  response->set_modem_id(identity_.modem_id);
  response->set_mac(identity_.mac.empty() ? "none" : identity_.mac);
  node_.core.call([&] {
    const link::DriverStatus& status = node_.link.driver.status();
    v1::DriverStatus* driver = response->mutable_driver();
    driver->set_name(identity_.driver);
    driver->set_state(link::to_string(status.state));
    driver->set_summary(link::describe(status, std::chrono::system_clock::now()));
    driver->set_last_error(status.last_error);
    driver->set_failures(status.failures);
    driver->set_starts(status.starts);
    driver->set_modem(node_.link.driver.modem());

    const mac::Cycle& cycle = node_.link.mac.cycle();
    for (const mac::Slot& slot : cycle) *response->add_cycle() = to_proto(slot);
    response->set_cycle_seconds(cycle.empty() ? 0 : mac::cycle_seconds(cycle));
    const mac::MacStatus mac = node_.link.mac.status();
    for (int32_t id : mac.known_ids) response->add_known_nodes(id);
    if (!mac.blank_rule.empty()) response->set_blank_rule(mac.blank_rule);

    const link::LinkStats& stats = node_.link.controller.stats();
    v1::LinkCounters* counters = response->mutable_counters();
    counters->set_transmissions_sent(stats.transmissions_sent);
    counters->set_transmissions_failed(stats.transmissions_failed);
    counters->set_data_received(stats.data_received);
    counters->set_acks_received(stats.acks_received);
    counters->set_messages_delivered(stats.messages_delivered);
    counters->set_duplicates_dropped(node_.queues.duplicates());
    counters->set_malformed_frames(node_.queues.malformed_frames());
    counters->set_stale_refused(node_.queues.stale_refused());
    const queue::AuthRefusals& refused = node_.queues.auth_refusals();
    counters->set_auth_failed(refused.auth_failed);
    counters->set_auth_replayed(refused.replayed);
    counters->set_auth_stale(refused.stale);
    const link::DriverCounters lost = node_.link.driver.counters();
    counters->set_lost_half_duplex(lost.lost_half_duplex);
    counters->set_lost_collision(lost.lost_collision);
    for (const auto& [kind, count] : lost.bad_input) (*counters->mutable_bad_input())[kind] = count;
    counters->set_receptions_with_figures(stats.receptions_with_figures);
    counters->set_bad_frames_received(stats.bad_frames_received);
  });
  return grpc::Status::OK;
}

grpc::Status AcommsService::SetCycle(grpc::ServerContext* context, const v1::SetCycleRequest* request,
                                     v1::SetCycleResponse* response) {
  if (grpc::Status denied = allowed(*context, "SetCycle"); !denied.ok()) return denied;
  // The MAC says whether its cycle can be set: the service names no MAC.
  if (std::string refusal = node_.link.mac.cycle_not_settable_reason(); !refusal.empty()) {
    return {grpc::StatusCode::FAILED_PRECONDITION, refusal};
  }
  if (request->slot_size() > 1000) {
    return {grpc::StatusCode::INVALID_ARGUMENT, "a cycle has at most 1000 slots"};
  }
  v1::MacConfig config;
  *config.mutable_slot() = request->slot();
  mac::Cycle cycle = mac::cycle_from_config(config);
  try {
    mac::check_cycle(cycle, "slot");
    node_.core.call([&] { node_.link.mac.set_cycle(cycle); });
  } catch (const std::invalid_argument& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  }
  response->set_cycle_seconds(mac::cycle_seconds(cycle));
  return grpc::Status::OK;
}

}  // namespace acomms::service
