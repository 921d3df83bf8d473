// LinkStatus, SetCycle and SetLinkEnabled: each link's driver and MAC.
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

grpc::Status AcommsService::find_link(const std::string& name, Link** out) {
  if (name.empty()) {
    *out = &node_.links.front();
    return grpc::Status::OK;
  }
  std::string known;
  for (Link& link : node_.links) {
    if (link.name == name) {
      *out = &link;
      return grpc::Status::OK;
    }
    known += (known.empty() ? "\"" : ", \"") + link.name + "\"";
  }
  return {grpc::StatusCode::NOT_FOUND, "no link \"" + name + "\" (this node's links: " + known + ")"};
}

// One link's status (core thread). The queues' counters (duplicates,
// malformed, stale) are the node's: every link reports them.
static void fill_link_status(const Link& link, const DaemonIdentity& identity, const Node& node,
                             v1::LinkStatusResponse* response) {
  const queue::QueueManager& queues = node.queues;
  response->set_name(link.name);
  response->set_modem_id(identity.modem_id);
  response->set_enabled(link.controller.enabled());
  response->set_cost(link.cost);
  const link::DriverStatus& status = link.driver.status();
  v1::DriverStatus* driver = response->mutable_driver();
  driver->set_name(link.driver_name);
  driver->set_state(link::to_string(status.state));
  driver->set_summary(link::describe(status, std::chrono::system_clock::now()));
  driver->set_last_error(status.last_error);
  driver->set_failures(status.failures);
  driver->set_starts(status.starts);
  driver->set_modem(link.driver.modem());

  response->set_mac(link.mac_name.empty() ? "none" : link.mac_name);
  const mac::Cycle& cycle = link.mac.cycle();
  for (const mac::Slot& slot : cycle) *response->add_cycle() = to_proto(slot);
  response->set_cycle_seconds(cycle.empty() ? 0 : mac::cycle_seconds(cycle));
  const mac::MacStatus mac = link.mac.status();
  for (int32_t id : mac.known_ids) response->add_known_nodes(id);
  if (!mac.blank_rule.empty()) response->set_blank_rule(mac.blank_rule);

  const link::LinkStats& stats = link.controller.stats();
  v1::LinkCounters* counters = response->mutable_counters();
  counters->set_transmissions_sent(stats.transmissions_sent);
  counters->set_transmissions_failed(stats.transmissions_failed);
  counters->set_data_received(stats.data_received);
  counters->set_acks_received(stats.acks_received);
  counters->set_messages_delivered(stats.messages_delivered);
  counters->set_duplicates_dropped(queues.duplicates());
  counters->set_malformed_frames(queues.malformed_frames());
  counters->set_stale_refused(queues.stale_refused());
  const queue::AuthRefusals& refused = queues.auth_refusals();
  counters->set_auth_failed(refused.auth_failed);
  counters->set_auth_replayed(refused.replayed);
  counters->set_auth_stale(refused.stale);
  const link::DriverCounters lost = link.driver.counters();
  counters->set_lost_half_duplex(lost.lost_half_duplex);
  counters->set_lost_collision(lost.lost_collision);
  for (const auto& [kind, count] : lost.bad_input) (*counters->mutable_bad_input())[kind] = count;
  counters->set_receptions_with_figures(stats.receptions_with_figures);
  counters->set_bad_frames_received(stats.bad_frames_received);
  if (node.consistency_link_status) {
    node.consistency_link_status(static_cast<int>(&link - node.links.data()), response);
  }
}

grpc::Status AcommsService::LinkStatus(grpc::ServerContext* context, const v1::LinkStatusRequest* request,
                                       v1::LinkStatusResponse* response) {
  if (grpc::Status denied = allowed(*context, "LinkStatus"); !denied.ok()) return denied;
  Link* asked = nullptr;
  if (grpc::Status found = find_link(request->link(), &asked); !found.ok()) return found;
  node_.core.call([&] {
    // The top-level fields: the link asked for, or the first (what a
    // client written for one link reads); `links`: the one, or all.
    fill_link_status(*asked, identity_, node_, response);
    for (const Link& link : node_.links) {
      if (request->link().empty() || &link == asked) {
        fill_link_status(link, identity_, node_, response->add_links());
      }
    }
  });
  return grpc::Status::OK;
}

grpc::Status AcommsService::SetLinkEnabled(grpc::ServerContext* context, const v1::SetLinkEnabledRequest* request,
                                           v1::SetLinkEnabledResponse* response) {
  if (grpc::Status denied = allowed(*context, "SetLinkEnabled"); !denied.ok()) return denied;
  if (request->link().empty()) return {grpc::StatusCode::INVALID_ARGUMENT, "link: name the link to change"};
  Link* link = nullptr;
  if (grpc::Status found = find_link(request->link(), &link); !found.ok()) return found;
  node_.core.call([&] {
    link->controller.set_enabled(request->enabled());
    response->set_enabled(link->controller.enabled());
  });
  return grpc::Status::OK;
}

grpc::Status AcommsService::SetCycle(grpc::ServerContext* context, const v1::SetCycleRequest* request,
                                     v1::SetCycleResponse* response) {
  if (grpc::Status denied = allowed(*context, "SetCycle"); !denied.ok()) return denied;
  Link* link = nullptr;
  if (grpc::Status found = find_link(request->link(), &link); !found.ok()) return found;
  // The MAC says whether its cycle can be set: the service names no MAC.
  if (std::string refusal = link->mac.cycle_not_settable_reason(); !refusal.empty()) {
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
    node_.core.call([&] { link->mac.set_cycle(cycle); });
  } catch (const std::invalid_argument& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  }
  response->set_cycle_seconds(mac::cycle_seconds(cycle));
  return grpc::Status::OK;
}

}  // namespace acomms::service
