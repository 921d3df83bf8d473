#include "daemon.h"

#include <spdlog/spdlog.h>

#include "core/systemd_notify.h"
#include "message_definitions.h"

namespace acomms {

Daemon::Daemon(const v1::Config& config) : config_(config) {
  store_ = std::make_unique<store::Store>(config_.data_dir());
  codec_ = make_codec(config_.dccl());
  core_ = std::make_unique<core::EventLoop>();
  core_->start();

  service::DaemonFacts facts;
  facts.version = ACOMMS_VERSION;
  facts.data_dir = config_.data_dir();
  facts.schema_version = store_->schema_version();
  facts.driver = config_.driver().name();
  facts.mac = config_.mac().name();
  facts.modem_id = config_.driver().modem_id();
  facts.dccl_types = static_cast<int32_t>(codec_->types().size());
  api_ = std::make_unique<service::AcommsService>(std::move(facts));

  server_ = std::make_unique<service::GrpcServer>(
      service::Endpoints{config_.grpc().unix_socket(), config_.grpc().tcp_listen()},
      std::vector<grpc::Service*>{api_.get()});
  server_->set_serving(true);
  core::systemd_notify("READY=1\nSTATUS=serving");
  spdlog::info("acommsd {} serving (data dir {})", ACOMMS_VERSION, config_.data_dir());
}

Daemon::~Daemon() { stop(); }

void Daemon::stop() {
  if (!server_ && !core_ && !store_) return;
  core::systemd_notify("STOPPING=1");
  if (server_) server_->shutdown(std::chrono::seconds(2));
  server_.reset();
  if (core_) core_->stop();
  core_.reset();
  codec_.reset();
  store_.reset();
  spdlog::info("acommsd stopped");
}

}  // namespace acomms
