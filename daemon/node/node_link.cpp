#include "node/node_link.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>

#include "core/core_thread.h"
#include "mac/mac_factory.h"

namespace acomms::node {

NodeLink::NodeLink(const v1::LinkConfig& config, int index, LinkParts& parts)
    : config_(config), queues_(parts.queues), own_id_(parts.own_id) {
  // Errors name the link when there are several; one link's read as before.
  const std::string where = parts.link_count > 1 ? "link \"" + config_.name() + "\": " : "";
  const std::string& name = config_.driver().name();
  auto known = parts.drivers.names();
  if (std::find(known.begin(), known.end(), name) == known.end()) {
    std::string list;
    for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
    throw std::runtime_error(where + "driver.name \"" + name + "\" is not a driver (known: " + list + ")");
  }
  const v1::DriverConfig& driver_config = config_.driver();
  link::DriverContext context{driver_config, parts.scheduler, &parts.core.context(), &parts.node_position,
                              parts.models};
  // Built once now so that a bad driver block is a start-up error.
  try {
    (void)parts.drivers.create(name, context);
  } catch (const link::DriverError&) {
    // The device itself is the supervisor's concern: it retries.
  } catch (const std::exception& e) {
    throw std::runtime_error(where + "driver " + name + ": " + e.what());
  }
  link::SupervisorOptions options = link::SupervisorOptions::from_config(driver_config);
  options.driver_name = parts.link_count > 1 ? config_.name() + "/" + name : name;
  driver_ = std::make_unique<link::DriverSupervisor>(
      [&parts, &driver_config, name] {
        link::DriverContext context{driver_config, parts.scheduler, &parts.core.context(), &parts.node_position,
                                    parts.models};
        return parts.drivers.create(name, context);
      },
      parts.scheduler, options);
  try {
    mac_ = mac::make_mac(config_.mac(), parts.own_id, parts.scheduler);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(where + "mac config: " + e.what());
  }
  link::LinkOptions link_options = link::LinkOptions::from_config(config_.mac(), parts.scheduler.clock());
  link_options.scheduler = &parts.scheduler;  // deadlines of driver-specific requests
  link_options.after_receipt_durable = parts.after_receipt_durable;
  link_options.choice = &parts.choice;
  link_options.link_index = index;
  link_options.enabled = !config_.has_enabled() || config_.enabled();
  if (name == "micromodem" && driver_config.micromodem().has_prediction()) {
    PredictionSources sources{parts.own_id, &parts.node_position, parts.modem_positions, parts.environment,
                              parts.models, [&core = parts.core](std::function<void()> task) { core.post(std::move(task)); },
                              [&clock = parts.scheduler.clock()] { return clock.now_seconds(); }};
    try {
      prediction_ = LinkPrediction::create(driver_config.micromodem().prediction(), std::move(sources));
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(where + e.what());
    }
    link_options.predict = [p = prediction_.get()](const v1::ModemTransmission& heard, v1::LinkFigures& figures) {
      p->predict(heard, figures);
    };
  }
  // Who this link heard, at which rate: where a telemetry gap's packets
  // were lost (record_unheard).
  auto deliver = [this, deliver = parts.deliver, &clock = parts.scheduler.clock()](
                     queue::ReceivedMessage message, const v1::ModemTransmission& from) {
    heard_[from.src()] = Heard{clock.now_seconds(), from.rate()};
    deliver(std::move(message), from);
  };
  controller_ = std::make_unique<link::LinkController>(parts.own_id, parts.queues, *mac_, *driver_, std::move(deliver),
                                                       link_options);
  // A failed driver's link carries nothing until it runs again: what waited
  // for its ACK may go on another link (link_choice.h).
  driver_->set_status_callback([controller = controller_.get()](const link::DriverStatus& status) {
    controller->on_driver_state(status.state == link::DriverState::kRunning);
  });
  // The driver's bytes, kept for debugging (link/raw_log.h) when the driver
  // says they are worth the disk (link/driver_registry.h, DriverTraits).
  if (const auto& raw_log_bytes = parts.drivers.traits(name).raw_log_bytes) {
    const std::string file = parts.link_count > 1 ? "link-raw-" + config_.name() + ".log" : "link-raw.log";
    raw_log_ = std::make_unique<link::RawLog>(std::filesystem::path(parts.data_dir) / file,
                                              raw_log_bytes(driver_config), parts.scheduler.clock());
    controller_->set_raw_tap([log = raw_log_.get()](std::string_view raw, bool outgoing) { log->record(raw, outgoing); });
  }
  if (config_.has_enable_above_depth_m()) depth_.emplace(config_.enable_above_depth_m());
}

std::optional<NodeLink::Heard> NodeLink::last_heard(int32_t src) const {
  auto it = heard_.find(src);
  if (it == heard_.end()) return std::nullopt;
  return it->second;
}

void NodeLink::record_unheard(int32_t src) {
  ACOMMS_ASSERT_CORE_THREAD();
  v1::LinkFigures figures;
  figures.set_transmission_src(src);
  figures.set_decoded(false);
  figures.set_link(config_.name());
  if (std::optional<Heard> heard = last_heard(src)) figures.set_rate(heard->rate);
  if (prediction_) {
    v1::ModemTransmission unheard;
    unheard.set_type(v1::ModemTransmission::DATA);
    unheard.set_src(src);
    unheard.set_dest(own_id_);
    unheard.set_rate(figures.rate());
    prediction_->predict(unheard, figures);
  }
  queues_.record_packet(src, own_id_, figures.SerializeAsString());
}

NodeLink::~NodeLink() {
  // The controller goes first: a supervisor stopping after it must not call it.
  driver_->set_status_callback(nullptr);
}

void NodeLink::on_depth(double depth_m) {
  if (!depth_) return;
  if (std::optional<bool> enable = depth_->on_depth(depth_m)) {
    // The controller logs the change; this says why.
    if (controller_->set_enabled(*enable)) {
      spdlog::info("link {}: depth {:.1f} m crossed enable_above_depth_m {}", config_.name(), depth_m,
                   depth_->threshold_m());
    }
  }
}

}  // namespace acomms::node
