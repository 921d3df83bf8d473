#pragma once
// acommsd assembled: store (with its group-commit writer and the message
// journal), DCCL codec, queues, core thread and gRPC endpoint, started in
// that order (the API answers only once what it reports on is up) and
// stopped in the reverse order.

#include <memory>

#include "acomms/v1/config.pb.h"
#include <asio/steady_timer.hpp>

#include "core/clock.h"
#include "core/event_loop.h"
#include "core/scheduler.h"
#include "link/driver_registry.h"
#include "link/driver_supervisor.h"
#include "link/link_choice.h"
#include "link/link_controller.h"
#include "link/raw_log.h"
#include "mac/mac.h"
#include "node/consistency_watch.h"
#include "node/definition_loader.h"
#include "node/gram_setup.h"
#include "node/node_link.h"
#include "node/received_message_router.h"
#include "node/unheard_links.h"
#include "node/unheard_packets.h"
#include "dccl/codec.h"
#include "queue/durable_receipts.h"
#include "queue/queue_manager.h"
#include "queue/event_log_reader.h"
#include "queue/event_log_retention.h"
#include "queue/sqlite_journal.h"
#include "queue/submitter.h"
#include "route/forwarder.h"
#include "store/group_commit_writer.h"
#include "service/gram_service.h"
#include "service/grpc_server.h"
#include "service/acomms_service.h"
#include "service/subscriber_hub.h"
#include "store/store.h"
#include "core/node_position.h"
#include "node/modem_positions.h"
#include "telemetry/telemetry_node.h"
#include "telemetry/track_reader.h"

namespace acomms::node {

class Daemon {
 public:
  // Opens the store and starts serving. Throws (StoreError,
  // std::runtime_error) with a message fit for the operator.
  explicit Daemon(const v1::Config& config);
  // Same as stop().
  ~Daemon();

  // Stop accepting calls, let in-flight ones finish, stop the core, flush
  // and close the store. Idempotent.
  void stop();

  // SIGHUP: re-reads the API's TLS certificates (logs the outcome).
  void reload_tls();
  // SIGHUP: re-reads the auth keyring (logs the outcome; a keyring that
  // does not load leaves the old keys in use). Nothing without auth.
  void reload_keyring();

 private:
  // The constructor's work, in the order of the file comment.
  void start();
  void schedule_expiry();
  void build_links();
  void build_routing();
  void build_consistency();
  void schedule_depth_check();
  void build_telemetry(const telemetry::StoredStreams& stored);

  v1::Config config_;
  int32_t own_id_ = 1;  // the node's modem id on every link (core/node_links.h)
  core::SystemClock clock_;
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<store::GroupCommitWriter> writer_;
  std::unique_ptr<queue::SqliteJournal> journal_;
  std::unique_ptr<queue::EventLogReader> events_;
  std::unique_ptr<dccl::Codec> codec_;
  // Authenticated types' keys (null without auth); SIGHUP replaces them.
  std::shared_ptr<dccl::MessageAuthenticator> authenticator_;
  // Owned by the core thread once it runs.
  std::unique_ptr<queue::QueueManager> queues_;
  std::unique_ptr<DefinitionLoader> definitions_;
  // The gateway (config `routing`); null without. The queues call it.
  // Its notes and learned routes go to the store through route_journal_.
  std::unique_ptr<route::RouteJournal> route_journal_;
  std::unique_ptr<route::Forwarder> forwarder_;
  service::SubscriberHub subscribers_;
  std::unique_ptr<core::EventLoop> core_;
  // Submit's way into the queues, through the core thread.
  std::unique_ptr<queue::Submitter> submitter_;
  std::unique_ptr<asio::steady_timer> expiry_timer_;
  // The links, on the core thread: each its driver (supervised), MAC, and
  // the LinkController that binds them to the queues (node/node_link.h),
  // and the choice of link they share (link/link_choice.h).
  std::unique_ptr<core::AsioScheduler> scheduler_;
  link::DriverRegistry drivers_;
  // Where the links' received messages go; publishes through its own
  // when-stored chain (queue/durable_receipts.h), apart from the ACKs'.
  std::unique_ptr<ReceivedMessageRouter> received_;
  std::unique_ptr<link::LinkChoice> choice_;
  std::unique_ptr<LinkParts> link_parts_;
  std::vector<std::unique_ptr<NodeLink>> links_;
  // Consistency across the fleet (config `consistency`): the announce the
  // queues piggyback on the links, and what neighbours announced.
  std::unique_ptr<ConsistencyWatch> consistency_;
  // Applies the navigation input's depth to links enabled by depth.
  std::unique_ptr<asio::steady_timer> depth_timer_;
  // Prunes the event log on the core thread's schedule, on the writer.
  std::unique_ptr<queue::EventLogRetention> retention_;
  // Position telemetry (core thread): navigation in, streams out, received
  // streams to positions; the node's newest fix for the sim driver.
  telemetry::NodeSettings telemetry_settings_;
  core::NodePosition node_position_;
  ModemPositions modem_positions_;  // the others', from their telemetry (core thread)
  // Packets only a telemetry gap tells of, as packet events (before
  // telemetry_, which calls it).
  std::unique_ptr<UnheardPackets> unheard_;
  std::unique_ptr<telemetry::TelemetryNode> telemetry_;
  std::unique_ptr<telemetry::TrackReader> track_;
  // Who may call what on the API (config auth); outlives both services.
  std::unique_ptr<service::ApiRoles> roles_;
  std::unique_ptr<service::AcommsService> api_;
  // GRAM: the environment the vehicle knows and the model worker pool.
  GramParts gram_;
  std::unique_ptr<service::GramService> gram_api_;
  std::unique_ptr<service::GrpcServer> server_;
};

}  // namespace acomms::node
