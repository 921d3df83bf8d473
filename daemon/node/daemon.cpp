#include "node/daemon.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>

#include "core/systemd_notify.h"
#include "mac/mac_factory.h"
#include "node/auth_setup.h"
#include "node/codec_setup.h"
#include "service/position_message.h"

namespace acomms::node {

Daemon::Daemon(const v1::Config& config) : config_(config) {
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
  const auto own_id = static_cast<int32_t>(config_.driver().modem_id());
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
      [this](const v1::ReceivedMessage& message) { subscribers_.publish(message); });
  events_ = std::make_unique<queue::EventLogReader>(store_->db().path());
  codec_ = make_codec(config_.dccl());
  // Before the queues restore: messages of these types are in the journal.
  DefinitionLoader::load_recorded(*codec_, api_definitions);
  // Before the queues restore: stored messages of these types are sealed
  // as they are queued again.
  authenticator_ = make_authenticator(config_.auth(), *codec_);
  try {
    queues_ = std::make_unique<queue::QueueManager>(*codec_, config_.queue(),
                                                    static_cast<int32_t>(config_.driver().modem_id()),
                                                    clock_, *journal_);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("queue config: ") + e.what());
  }
  authenticate_queues(config_.auth(), *queues_);
  queues_->restore();
  definitions_ = std::make_unique<DefinitionLoader>(
      *codec_, *queues_, *writer_, (std::filesystem::path(config_.data_dir()) / "definitions").string());
  core_ = std::make_unique<core::EventLoop>();
  submitter_ = std::make_unique<queue::Submitter>(
      *queues_, [core = core_.get()](std::function<void()> work) { core->post(std::move(work)); });
  expiry_timer_ = std::make_unique<asio::steady_timer>(core_->context());
  build_link();
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
    link_->start();  // the supervisor retries a driver that fails to start
  });

  service::DaemonIdentity identity;
  identity.version = ACOMMS_VERSION;
  identity.data_dir = config_.data_dir();
  identity.schema_version = store_->schema_version();
  identity.driver = config_.driver().name();
  identity.mac = config_.mac().name();
  identity.modem_id = config_.driver().modem_id();
  try {
    roles_ = std::make_unique<service::ApiRoles>(config_.auth());
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  api_ = std::make_unique<service::AcommsService>(
      std::move(identity),
      service::Node{*codec_, *queues_, *submitter_, *core_, {*mac_, *driver_, *link_}, *definitions_, *events_,
                    subscribers_, *telemetry_, *track_},
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

// Driver, MAC and the LinkController that binds them to the queues (the
// link's binding). Configuration
// mistakes (unknown driver, bad cycle) stop the start-up here; device
// failures later are the supervisor's to retry.
void Daemon::build_link() {
  const auto own_id = static_cast<int32_t>(config_.driver().modem_id());
  scheduler_ = std::make_unique<core::AsioScheduler>(core_->context(), clock_);
  drivers_ = link::DriverRegistry::linked();  // every driver plugin linked in
  const std::string& name = config_.driver().name();
  auto known = drivers_.names();
  if (std::find(known.begin(), known.end(), name) == known.end()) {
    std::string list;
    for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
    throw std::runtime_error("driver.name \"" + name + "\" is not a driver (known: " + list + ")");
  }
  link::DriverContext context{config_.driver(), *scheduler_, &core_->context(), &node_position_,
                              gram_.pool.get()};
  // Built once now so that a bad driver block is a start-up error.
  try {
    (void)drivers_.create(name, context);
  } catch (const link::DriverError&) {
    // The device itself is the supervisor's concern: it retries.
  } catch (const std::exception& e) {
    throw std::runtime_error("driver " + name + ": " + e.what());
  }
  link::SupervisorOptions options = link::SupervisorOptions::from_config(config_.driver());
  options.driver_name = name;
  driver_ = std::make_unique<link::DriverSupervisor>(
      [this, name] {
        link::DriverContext context{config_.driver(), *scheduler_, &core_->context(), &node_position_,
                                    gram_.pool.get()};
        return drivers_.create(name, context);
      },
      *scheduler_, options);
  try {
    mac_ = mac::make_mac(config_.mac(), own_id, *scheduler_);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("mac config: ") + e.what());
  }
  link_ = std::make_unique<link::LinkController>(
      own_id, *queues_, *mac_, *driver_,
      [router = received_.get()](queue::ReceivedMessage message, const v1::ModemTransmission& from) {
        router->route(message, from);
      },
      [this] {
        link::LinkOptions options = link::LinkOptions::from_config(config_.mac(), scheduler_->clock());
        options.scheduler = scheduler_.get();  // deadlines of driver-specific requests
        // Daemon::stop flushes the writer before the core goes, so no
        // commit callback outlives it.
        options.after_receipt_durable =
            queue::durable_receipts(*journal_, [this](queue::Task task) { core_->post(std::move(task)); });
        return options;
      }());
  // The driver's bytes, kept for debugging (link/raw_log.h) when the driver
  // says they are worth the disk (link/driver_registry.h, DriverTraits).
  if (const auto& raw_log_bytes = drivers_.traits(name).raw_log_bytes) {
    raw_log_ = std::make_unique<link::RawLog>(std::filesystem::path(config_.data_dir()) / "link-raw.log",
                                              raw_log_bytes(config_.driver()), clock_);
    link_->set_raw_tap([this](std::string_view raw, bool outgoing) { raw_log_->record(raw, outgoing); });
  }
}

// Telemetry sends through the Submit path (durable before queued) and
// publishes what it reconstructs as acomms.telemetry.Position.
void Daemon::build_telemetry(const telemetry::StoredStreams& /*stored*/) {
  const auto own_id = static_cast<int32_t>(config_.driver().modem_id());
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
      subscribers_.publish(
          service::to_received_message(service::to_position(p, telemetry_settings_), own_id, clock_.now_seconds()));
    }
  };
  telemetry_ = std::make_unique<telemetry::TelemetryNode>(telemetry_settings_, own_id, *codec_, *writer_,
                                                           &node_position_, submit, publish);
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
  if (core_ && link_) core_->call([this] { link_->stop(); });
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
  link_.reset();
  received_.reset();
  mac_.reset();
  driver_.reset();
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
