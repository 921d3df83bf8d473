#include "node/daemon.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>

#include "core/node_links.h"
#include "core/systemd_notify.h"
#include "node/auth_setup.h"
#include "node/codec_setup.h"
#include "service/position_message.h"

namespace acomms::node {

Daemon::Daemon(const v1::Config& config) : config_(config) {
  try {
    own_id_ = core::node_id(config_);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  // A start that fails half way (the TCP port is taken, say) must stop what
  // it started, in order: the link on the core thread, then the core. The
  // members' destructors alone would stop the driver from this thread while
  // the core still runs it.
  try {
    start();
  } catch (...) {
    stop();
    throw;
  }
}

namespace {

queue::RetentionPolicy retention_policy(const v1::StoreConfig& store) {
  queue::RetentionPolicy policy;
  if (store.has_event_retention_days()) policy.max_age_s = store.event_retention_days() * 86400.0;
  if (store.has_event_retention_mb()) policy.max_bytes = static_cast<int64_t>(store.event_retention_mb() * (1 << 20));
  return policy;
}

}  // namespace

void Daemon::start() {
  const int32_t own_id = own_id_;
  try {
    telemetry_settings_ = telemetry::node_settings(config_.telemetry(), own_id);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  telemetry::configure_queues(config_.mutable_queue(), telemetry_settings_);
  store_ = std::make_unique<store::Store>(config_.data_dir());
  std::vector<RecordedDefinition> api_definitions =
      DefinitionLoader::read_recorded(store_->db());
  const telemetry::StoredStreams telemetry_stored = telemetry::TelemetryNode::read_state(store_->db());
  gram_ = make_gram(config_.gram(), config_.data_dir(), store_->db());
  // From here on only the writer's thread touches the store's connection.
  writer_ = std::make_unique<store::GroupCommitWriter>(store_->db());
  journal_ = std::make_unique<queue::SqliteJournal>(*writer_);
  // Its when-stored chain counts the journal's failures from here on.
  received_ = std::make_unique<ReceivedMessageRouter>(
      [this](const queue::ReceivedMessage& message) { telemetry_->on_received(message); },
      queue::when_stored(*journal_),
      [this](const v1::ReceivedMessage& message) { subscribers_.publish(message); },
      [this](std::function<void()> work) { core_->post(std::move(work)); });
  events_ = std::make_unique<queue::EventLogReader>(store_->db().path());
  codec_ = make_codec(config_.dccl());
  // Before the queues restore: messages of these types are in the journal.
  DefinitionLoader::load_recorded(*codec_, api_definitions);
  // Before the queues restore: stored messages of these types are sealed
  // as they are queued again.
  authenticator_ = make_authenticator(config_.auth(), *codec_, own_id_);
  try {
    queues_ = std::make_unique<queue::QueueManager>(*codec_, config_.queue(), own_id_, clock_, *journal_);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("queue config: ") + e.what());
  }
  authenticate_queues(config_.auth(), *queues_);
  // Before the queues restore: custody messages come back into their queues.
  build_routing();
  queues_->restore();
  definitions_ = std::make_unique<DefinitionLoader>(
      *codec_, *queues_, *writer_, (std::filesystem::path(config_.data_dir()) / "definitions").string());
  core_ = std::make_unique<core::EventLoop>();
  submitter_ = std::make_unique<queue::Submitter>(
      *queues_, [core = core_.get()](std::function<void()> work) { core->post(std::move(work)); });
  expiry_timer_ = std::make_unique<asio::steady_timer>(core_->context());
  // Before any link starts: a mistake in the roles must stop the start
  // before anything goes on the air.
  try {
    roles_ = std::make_unique<service::ApiRoles>(config_.auth());
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  build_links();
  build_consistency();
  build_telemetry(telemetry_stored);
  retention_ = std::make_unique<queue::EventLogRetention>(
      *writer_, *scheduler_, retention_policy(config_.store()), [queues = queues_.get()](double now) {
        // What the duplicate filter reads back at the next start stays.
        return now - queues->duplicate_window_s();
      });
  core_->start();
  core_->call([this, &telemetry_stored] {
    // Before the link: the streams must be where the store says first.
    telemetry_->restore(telemetry_stored, *events_, *queues_);
    schedule_expiry();
    retention_->start();
    // Each supervisor retries a driver that fails to start.
    for (auto& link : links_) link->controller().start();
    schedule_depth_check();
  });

  service::DaemonIdentity identity;
  identity.version = ACOMMS_VERSION;
  identity.data_dir = config_.data_dir();
  identity.schema_version = store_->schema_version();
  // The first link's: what a client written for one link reads.
  identity.driver = links_.front()->config().driver().name();
  identity.mac = links_.front()->config().mac().name();
  identity.modem_id = static_cast<uint32_t>(own_id_);
  std::vector<service::Link> links;
  for (auto& link : links_) {
    links.push_back({link->name(), link->config().driver().name(), link->config().mac().name(),
                     link->config().cost(), link->mac(), link->driver(), link->controller()});
  }
  api_ = std::make_unique<service::AcommsService>(
      std::move(identity), service::Node{*codec_, *queues_, *submitter_, *core_, std::move(links), *definitions_,
                                         *events_, subscribers_, *telemetry_, *track_, forwarder_.get(),
                                         [this](v1::Status* status) { consistency_->fill(status); },
                                         [this](int link, v1::LinkStatusResponse* response) {
                                           consistency_->fill_link(link, response);
                                         }},
      *roles_);

  gram_api_ = std::make_unique<service::GramService>(*gram_.pool, *gram_.environment,
                                                     save_environment_to(*writer_), *roles_);

  server_ = std::make_unique<service::GrpcServer>(
      service::endpoints_of(config_.grpc()),
      std::vector<grpc::Service*>{api_.get(), gram_api_.get()});
  server_->set_serving(true);
  core::systemd_notify("READY=1\nSTATUS=serving");
  spdlog::info("acommsd {} serving (data dir {})", ACOMMS_VERSION, config_.data_dir());
}

Daemon::~Daemon() { stop(); }

void Daemon::reload_tls() {
  if (server_) server_->reload_tls();
}

void Daemon::reload_keyring() {
  if (authenticator_) node::reload_keyring(config_.auth(), *authenticator_);
}

// A gateway (config `routing`, route/forwarder.h): custody commits are
// posted to the core, which runs by the time anything is received.
void Daemon::build_routing() {
  if (!config_.has_routing()) return;
  std::vector<std::string> links;
  for (const v1::LinkConfig& link : core::node_links(config_)) links.push_back(link.name());
  try {
    const double ttl_s = queue::resolve_policy({}, config_.queue().defaults(), "queue.defaults").ttl_s;
    route_journal_ = std::make_unique<route::RouteJournal>(*writer_);
    forwarder_ = std::make_unique<route::Forwarder>(
        config_.routing(), own_id_, std::move(links), *codec_, *queues_, clock_, ttl_s,
        [this](std::function<void()> work) { core_->post(std::move(work)); }, route_journal_.get());
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("routing config: ") + e.what());
  }
  queues_->set_routing(forwarder_.get());
}

// The consistency announce (node/consistency_watch.h) rides in the links'
// frames: set before any link starts. The watch reads each link's MAC.
void Daemon::build_consistency() {
  std::vector<ConsistencyWatch::Link> links;
  for (auto& link : links_) links.push_back({link->name(), &link->config().mac(), &link->mac()});
  try {
    consistency_ = std::make_unique<ConsistencyWatch>(config_.consistency(), *codec_, std::move(links));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("consistency config: ") + e.what());
  }
  // Disabled: the status still shows this node's own digest, but the
  // announce id is not taken from the node's types, nothing is announced
  // and a frame with that id is decoded as any message.
  if (!consistency_->enabled()) return;
  const uint32_t announce_id = consistency_->dccl_id();
  if (forwarder_ && forwarder_->envelope_id() == announce_id) {
    throw std::runtime_error("consistency config: consistency.announce_id " + std::to_string(announce_id) +
                             " is routing.envelope_id too: choose another for one of them");
  }
  // A type loaded later (LoadDefinitions) with that id is refused naming it.
  codec_->reserve_id(static_cast<int>(announce_id), "consistency.announce_id (the consistency announce)");
  queues_->set_piggyback(consistency_.get());
}

// Every link (node/node_link.h) and the choice of link they share.
// Configuration mistakes (unknown driver, bad cycle) stop the start-up here;
// device failures later are each link's supervisor's to retry.
void Daemon::build_links() {
  scheduler_ = std::make_unique<core::AsioScheduler>(core_->context(), clock_);
  drivers_ = link::DriverRegistry::linked();  // every driver plugin linked in
  std::vector<v1::LinkConfig> configured = core::node_links(config_);
  try {
    choice_ = std::make_unique<link::LinkChoice>(
        link::LinkChoice::from_config(configured, config_.queue(), clock_.now_seconds()));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("queue config: ") + e.what());
  }
  link_parts_ = std::make_unique<LinkParts>(LinkParts{
      .own_id = own_id_,
      .data_dir = config_.data_dir(),
      .link_count = static_cast<int>(configured.size()),
      .scheduler = *scheduler_,
      .core = *core_,
      .drivers = drivers_,
      .node_position = node_position_,
      .models = gram_.pool.get(),
      .queues = *queues_,
      .choice = *choice_,
      .deliver = [router = received_.get()](queue::ReceivedMessage message, const v1::ModemTransmission& from) {
        router->route(std::move(message), from);
      },
      // Daemon::stop flushes the writer before the core goes, so no
      // commit callback outlives it.
      .after_receipt_durable =
          queue::durable_receipts(*journal_, [this](queue::Task task) { core_->post(std::move(task)); }),
      .modem_positions = &modem_positions_,
      .environment = gram_.environment.get(),
  });
  for (size_t i = 0; i < configured.size(); ++i) {
    links_.push_back(std::make_unique<NodeLink>(configured[i], static_cast<int>(i), *link_parts_));
  }
  depth_timer_ = std::make_unique<asio::steady_timer>(core_->context());
}

// Links enabled by depth follow the newest navigation fix (z up, so depth
// is -z), looked at once a second: a link's state changes only when the
// depth crosses its threshold (link/depth_switch.h).
void Daemon::schedule_depth_check() {
  depth_timer_->expires_after(std::chrono::seconds(1));
  depth_timer_->async_wait([this](const std::error_code& error) {
    if (error) return;
    if (std::optional<core::NodeFix> fix = node_position_.latest()) {
      for (auto& link : links_) link->on_depth(-fix->z);
    }
    schedule_depth_check();
  });
}

// Telemetry sends through the Submit path (durable before queued) and
// publishes what it reconstructs as acomms.telemetry.Position.
void Daemon::build_telemetry(const telemetry::StoredStreams& /*stored*/) {
  const int32_t own_id = own_id_;
  auto submit = [this](std::unique_ptr<google::protobuf::Message> message, std::function<void(bool)> done) {
    std::shared_ptr<google::protobuf::Message> owned(std::move(message));
    submitter_->submit(*owned, 0, [this, owned, done = std::move(done)](queue::SubmitResult result) {
      if (!result.ok()) spdlog::warn("telemetry: {} not queued: {}", owned->GetTypeName(), result.text);
      // The result may come on any thread; the stream is the core's.
      core_->post([done, ok = result.ok()] { done(ok); });
    });
  };
  auto publish = [this, own_id](const std::vector<telemetry::ReceivedPosition>& positions) {
    for (const telemetry::ReceivedPosition& p : positions) {
      // Where the sender is, for the model's prediction of what its
      // packets should give here (node/link_prediction.h).
      modem_positions_.set(p.src, core::NodeFix{static_cast<double>(p.time_s), p.position_m[0], p.position_m[1],
                                                p.position_m[2]});
      subscribers_.publish(
          service::to_received_message(service::to_position(p, telemetry_settings_), own_id, p.received_s, p.seq));
    }
  };
  telemetry_ = std::make_unique<telemetry::TelemetryNode>(telemetry_settings_, own_id, *codec_, *writer_,
                                                           &node_position_, submit, publish);
  // Positions take their numbers from the received sequence, so Subscribe's
  // `after` replays them among received messages.
  telemetry_->number_positions_with([queues = queues_.get()] { return queues->take_received_seq(); });
  // A gap in a sender's telemetry: packets sent and not received, on the
  // link that last heard it (node/unheard_packets.h).
  unheard_ = std::make_unique<UnheardPackets>(UnheardPackets::Hooks{
      [this](int32_t src) {
        uint64_t lost = 0;
        for (const auto& link : links_) lost += link->controller().lost_recorded(src);
        return lost;
      },
      [this](int32_t src) {
        NodeLink* heard_by = nullptr;
        double newest = 0;
        for (const auto& link : links_) {
          std::optional<NodeLink::Heard> heard = link->last_heard(src);
          if (heard && (heard_by == nullptr || heard->time_s > newest)) {
            heard_by = link.get();
            newest = heard->time_s;
          }
        }
        if (heard_by != nullptr) heard_by->record_unheard(src);
      },
      [this](int32_t src) {
        // The link that delivered the message after the gap heard the
        // sender last; another within the window makes it several.
        std::vector<double> times;
        for (const auto& link : links_) {
          if (std::optional<NodeLink::Heard> heard = link->last_heard(src)) times.push_back(heard->time_s);
        }
        if (times.size() < 2) return false;
        std::sort(times.begin(), times.end());
        return times[times.size() - 1] - times[times.size() - 2] <= UnheardPackets::kSeveralLinks_s;
      }});
  telemetry_->on_sequence([unheard = unheard_.get()](int32_t src, uint32_t missing, bool replayed) {
    unheard->on_sequence(src, missing, replayed);
  });
  track_ = std::make_unique<telemetry::TrackReader>(store_->db().path());
}

// Messages expire on time even when no transmission comes to notice them.
void Daemon::schedule_expiry() {
  expiry_timer_->expires_after(std::chrono::seconds(1));
  expiry_timer_->async_wait([this](const std::error_code& error) {
    if (error) return;
    queues_->expire();
    schedule_expiry();
  });
}

void Daemon::stop() {
  if (!server_ && !core_ && !store_ && !gram_.pool) return;
  core::systemd_notify("STOPPING=1");
  // The link stops first: the server's shutdown may take its whole grace
  // period (an idle client connection holds it), and nothing should go on
  // the air after the operator asked the daemon to stop. Calls still in
  // flight meanwhile are journaled and go out after the next start.
  if (core_ && !links_.empty()) {
    core_->call([this] {
      if (depth_timer_) depth_timer_->cancel();
      for (auto& link : links_) link->controller().stop();
    });
  }
  if (core_ && retention_) core_->call([this] { retention_->stop(); });
  // Subscribe streams would otherwise hold the server's shutdown up.
  subscribers_.close();
  if (server_) server_->shutdown(std::chrono::seconds(2));
  server_.reset();
  // Telemetry's messages are submitted from the core thread and answered
  // back on it: let those in flight finish while the core still runs.
  if (core_ && writer_ && writer_->running()) {
    try {
      writer_->flush();
    } catch (const std::exception& e) {
      spdlog::warn("store writer: last commit before stopping failed: {}", e.what());
    }
    core_->call([] {});
  }
  gram_api_.reset();
  if (core_) core_->stop();
  links_.clear();
  depth_timer_.reset();
  link_parts_.reset();
  choice_.reset();
  received_.reset();
  // After the driver (the simulator asks the pool for models): waiting
  // requests are answered, running ones cancelled, the workers joined.
  gram_.pool.reset();
  gram_.environment.reset();
  scheduler_.reset();
  expiry_timer_.reset();
  // Commit callbacks post to the core (received messages' ACKs): let any
  // still queued run while it exists, stopped, so their tasks never run.
  if (writer_ && writer_->running()) {
    try {
      writer_->flush();
    } catch (const std::exception& e) {
      spdlog::warn("store writer: a commit while stopping failed: {}", e.what());
    }
  }
  core_.reset();
  submitter_.reset();
  definitions_.reset();
  queues_.reset();
  forwarder_.reset();  // after the queues, which call it
  route_journal_.reset();  // after the forwarder, which writes through it (the writer is flushed above)
  consistency_.reset();  // after the queues, which call it (the core is stopped: nothing reads the MACs it points to)
  // Every event recorded so far reaches the disk before the store closes.
  if (writer_) {
    writer_->stop();
    // How well commits were shared: the figure to look at when Submit
    // throughput or the disk's wear is in question.
    store::GroupCommitWriter::Stats s = writer_->stats();
    spdlog::info("store writer: {} writes in {} commits (largest batch {}), {} failed; {:.1f} s committing, {:.1f} s busy",
                 s.committed, s.batches, s.max_batch, s.failed, s.commit_seconds, s.busy_seconds);
  }
  journal_.reset();
  writer_.reset();
  // After the writer: its last requests were telemetry's.
  telemetry_.reset();
  track_.reset();
  retention_.reset();  // after the writer: a step in flight refers to it
  codec_.reset();
  events_.reset();
  store_.reset();
  spdlog::info("acommsd stopped");
}

}  // namespace acomms::node
