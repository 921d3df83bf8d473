#include "sim/sim_driver.h"

#include <asio/post.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/core_thread.h"
#include "link/rate_table.h"
#include "link/transmission_rules.h"
#include "sim/loopback_medium.h"
#include "sim/pool_tl_grid_source.h"
#include "sim/sim_physics.h"
#include "util/seconds.h"

namespace acomms::drivers {

using v1::ModemTransmission;
using Clock = core::Clock;

namespace {

constexpr double kDefaultSoundSpeed = 1500;  // m/s, sea water
// Our transmissions older than this cannot overlap an arrival still to come.
constexpr auto kHistory = std::chrono::minutes(5);

bool overlap(Clock::time_point a_start, Clock::time_point a_end, Clock::time_point b_start,
             Clock::time_point b_end) {
  // Half-open: a packet ending exactly as another starts does not collide.
  return a_start < b_end && b_start < a_end;
}

void validate(const v1::DriverConfig& config) {
  const auto& sim = config.sim();
  auto bad = [](const std::string& what) { return std::invalid_argument("driver.sim." + what); };
  if (sim.sound_speed() < 0 || !std::isfinite(sim.sound_speed())) {
    throw bad("sound_speed must be > 0 m/s (0: 1500), got " + std::to_string(sim.sound_speed()));
  }
  if (!(sim.loss_probability() >= 0 && sim.loss_probability() <= 1)) {
    throw bad("loss_probability must be in [0, 1], got " + std::to_string(sim.loss_probability()));
  }
  if (sim.max_range_m() < 0 || !std::isfinite(sim.max_range_m())) {
    throw bad("max_range_m must be >= 0 (0: no range loss), got " + std::to_string(sim.max_range_m()));
  }
  if (sim.listen().empty() && sim.peers_size() > 0) {
    throw bad("peers are set but listen is empty: a loopback node needs its own address");
  }
}

std::unique_ptr<SimMedium> join_channel(const v1::DriverConfig& config, SimChannel* channel) {
  validate(config);
  if (channel == nullptr) throw std::invalid_argument("sim driver: no channel given");
  return channel->connect();
}

std::unique_ptr<SimMedium> loopback_or_alone(const v1::DriverConfig& config, asio::io_context* io_context) {
  validate(config);
  if (config.sim().listen().empty()) return nullptr;
  if (io_context == nullptr) {
    throw std::invalid_argument("driver.sim.listen is set but no event loop was given for the loopback socket");
  }
  std::vector<std::string> peers(config.sim().peers().begin(), config.sim().peers().end());
  return std::make_unique<LoopbackMedium>(*io_context, config.sim().listen(), peers);
}

}  // namespace

SimDriver::SimDriver(const v1::DriverConfig& config, core::Scheduler& scheduler,
                     std::shared_ptr<SimChannel> channel)
    : SimDriver(config, scheduler, join_channel(config, channel.get()), channel ? channel->seed() : 0) {}

SimDriver::SimDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, asio::io_context* io_context,
                     gram::ModelPool* models)
    : SimDriver(config, scheduler, loopback_or_alone(config, io_context), 0) {
  if (physics_ && io_context != nullptr && models != nullptr) {
    // The daemon's GRAM pool; answers posted to the core thread's event loop.
    physics_->set_source(std::make_shared<PoolTlGridSource>(
        *models, [io_context](std::function<void()> task) { asio::post(*io_context, std::move(task)); }));
  } else if (physics_ && io_context != nullptr) {
    // No pool (a program without the daemon): a worker thread of this
    // node's own, answers posted to the core thread's event loop.
    auto worker = std::make_shared<WorkerThread>();
    physics_->set_source(std::make_shared<ExecutorTlGridSource>(
        [worker](std::function<void()> task) { worker->post(std::move(task)); },
        [io_context](std::function<void()> task) { asio::post(*io_context, std::move(task)); }));
  }
}

void SimDriver::set_tl_grid_source(std::shared_ptr<TlGridSource> source) {
  if (physics_) physics_->set_source(std::move(source));
}

SimDriver::SimDriver(const v1::DriverConfig& config, core::Scheduler& scheduler,
                     std::unique_ptr<SimMedium> medium, uint32_t default_seed)
    : id_(link::own_modem_id(config)),
      position_{config.sim().position().x(), config.sim().position().y(), config.sim().position().z()},
      sound_speed_(config.sim().sound_speed() > 0 ? config.sim().sound_speed() : kDefaultSoundSpeed),
      loss_probability_(config.sim().loss_probability()),
      max_range_m_(config.sim().max_range_m()),
      scheduler_(scheduler),
      medium_(std::move(medium)),
      sequence_({"sim modem " + std::to_string(id_), id_},
                {[this](const ModemTransmission& tx, bool report) { return transmit(tx, report); }}) {
  if (config.sim().has_physics()) physics_ = SimPhysics::create(config.sim().physics(), id_);
  uint32_t seed = config.sim().seed() != 0 ? config.sim().seed() : default_seed;
  if (seed == 0) seed = std::random_device{}();
  // Mixed with the id so that nodes on one channel draw independently.
  std::seed_seq sequence{seed, static_cast<uint32_t>(id_)};
  rng_.seed(sequence);
}

SimDriver::~SimDriver() { stop(); }

void SimDriver::start(link::DriverCallbacks callbacks) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  if (physics_ && !physics_->has_source())
    throw link::DriverError("sim modem " + std::to_string(id_) +
                            ": driver.sim.physics needs a model worker (set_tl_grid_source) on a shared channel");
  sequence_.start(std::move(callbacks));
  if (medium_) {
    try {
      medium_->open([this](const SimEnvelope& envelope) { hear(envelope); },
                    [this](std::string_view bytes) {
                      if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(bytes, false);
                    });
    } catch (...) {
      sequence_.stop();
      throw;
    }
  }
  const SimPosition at = position();
  spdlog::info("sim modem {}: at ({}, {}, {}) m, c = {} m/s", id_, at.x, at.y, at.z, sound_speed_);
  if (physics_) {
    spdlog::info("sim modem {}: physics: SL {:.1f} dB, NL {:.1f} dB; asking the model for a TL grid", id_,
                 physics_->link_physics().source_level_db, physics_->noise_level_db());
    physics_->follow(at);
  }
}

void SimDriver::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  if (medium_) medium_->close();
  for (auto id : tasks_) scheduler_.cancel(id);
  tasks_.clear();
  arrivals_.clear();
  own_transmissions_.clear();
  busy_until_ = {};
  sequence_.stop();
}

void SimDriver::do_work() {
  ACOMMS_ASSERT_CORE_THREAD();
  sequence_.check_running();
  auto horizon = scheduler_.clock().now() - kHistory;
  std::erase_if(own_transmissions_, [&](const Interval& i) { return i.end < horizon; });
}

const SimStats& SimDriver::stats() const {
  stats_.garbage = medium_ ? medium_->garbage_received() : 0;
  return stats_;
}

uint16_t SimDriver::listen_port() const {
  auto* loopback = dynamic_cast<LoopbackMedium*>(medium_.get());
  return loopback ? loopback->local_port() : 0;
}

double SimDriver::loss_probability(double range_m) const {
  double range_loss = max_range_m_ > 0 ? std::min(1.0, range_m / max_range_m_) : 0.0;
  return 1.0 - (1.0 - loss_probability_) * (1.0 - range_loss);
}

double SimDriver::uniform() {
  // 53 random bits: the same numbers with every standard library.
  return static_cast<double>(rng_() >> 11) * 0x1.0p-53;
}

core::Scheduler::TaskId SimDriver::schedule(Clock::time_point when, std::function<void()> task) {
  auto id_holder = std::make_shared<core::Scheduler::TaskId>(0);
  auto id = scheduler_.at(when, [this, id_holder, task = std::move(task)] {
    tasks_.erase(*id_holder);
    task();
  });
  *id_holder = id;
  tasks_.insert(id);
  return id;
}

void SimDriver::initiate_transmission(const ModemTransmission& request) { sequence_.transmit(request); }

std::chrono::nanoseconds SimDriver::packet_air_time(int32_t rate, uint32_t num_frames) const {
  const link::ModemRate* row = link::find_rate(rate);
  return row ? link::packet_air_time(*row, num_frames) : std::chrono::nanoseconds(0);
}

std::chrono::nanoseconds SimDriver::ack_time(int32_t) const { return kTurnaround + link::kMiniPacket; }

link::DriverCounters SimDriver::counters() const { return {stats_.lost_half_duplex, stats_.lost_collision}; }

std::string SimDriver::transmit(ModemTransmission tx, bool report_result) {
  ACOMMS_ASSERT_CORE_THREAD();
  Clock::time_point now = scheduler_.clock().now();
  if (now < busy_until_) {
    char until[64];
    std::snprintf(until, sizeof until, "%.3f", util::seconds_since_epoch(busy_until_));
    return "modem " + std::to_string(id_) + " is busy transmitting until " + until;
  }
  // Polls, ACKs and other frameless packets are mini-packets.
  std::chrono::nanoseconds air_time = link::kMiniPacket;
  const link::ModemRate* rate = link::find_rate(tx.rate());
  if (tx.type() == ModemTransmission::DATA && tx.frame_size() > 0 && rate != nullptr) {
    air_time = link::packet_air_time(*rate, static_cast<uint32_t>(tx.frame_size()));
  }
  tx.set_time(util::seconds_since_epoch(now));
  Interval interval{now, now + air_time};
  busy_until_ = interval.end;
  own_transmissions_.push_back(interval);
  // Half-duplex: whatever is arriving while we transmit is lost to us.
  for (auto& [key, arrival] : arrivals_) {
    if (overlap(arrival.interval.start, arrival.interval.end, interval.start, interval.end)) arrival.deaf = true;
  }
  SimEnvelope envelope{id_, position(), now, air_time, tx};
  if (physics_) physics_->follow(envelope.position);
  ++stats_.sent;
  if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(encode(envelope), true);
  if (medium_) {
    std::string problem = medium_->send(envelope);
    if (!problem.empty()) spdlog::debug("sim modem {}: {}", id_, problem);
  }
  if (report_result) {
    // The modem says a packet has gone once it is all in the water.
    schedule(interval.end, [this, tx] { sequence_.report(tx, true, ""); });
  }
  return "";
}

void SimDriver::hear(const SimEnvelope& envelope) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!sequence_.running() || envelope.sender == id_) return;
  std::optional<SimHearing> heard = hearing(envelope, position(), sound_speed_);
  if (!heard) {
    spdlog::debug("sim modem {}: packet from {} too far to arrive", id_, envelope.sender);
    return;
  }
  ++stats_.heard;
  Arrival arrival;
  arrival.range_m = heard->range_m;
  arrival.interval.start = heard->start;
  arrival.interval.end = heard->end;
  arrival.envelope = envelope;
  for (auto& [key, other] : arrivals_) {
    if (overlap(other.interval.start, other.interval.end, arrival.interval.start, arrival.interval.end)) {
      other.collided = true;
      arrival.collided = true;
    }
  }
  for (const auto& own : own_transmissions_) {
    if (overlap(own.start, own.end, arrival.interval.start, arrival.interval.end)) arrival.deaf = true;
  }
  uint64_t key = next_arrival_++;
  auto end = arrival.interval.end;
  arrivals_.emplace(key, std::move(arrival));
  schedule(end, [this, key] { finish_arrival(key); });
}

void SimDriver::finish_arrival(uint64_t key) {
  auto it = arrivals_.find(key);
  if (it == arrivals_.end()) return;
  Arrival arrival = std::move(it->second);
  arrivals_.erase(it);
  if (arrival.collided) {
    ++stats_.lost_collision;
    note_lost(arrival, "in a collision with another packet");
  } else if (arrival.deaf) {
    ++stats_.lost_half_duplex;
    note_lost(arrival, "to half-duplex: it arrived while this node transmitted");
  } else if (physics_ ? !decodes(arrival) : uniform() < loss_probability(arrival.range_m)) {
    // decodes() counts its own "no model yet".
    if (!physics_ || arrival.judgement->modelled) ++stats_.lost_random;
    if (physics_ && arrival.judgement->modelled) report_failed(arrival);
    spdlog::debug("sim modem {}: packet from {} lost at {:.0f} m", id_, arrival.envelope.sender,
                  arrival.range_m);
  } else {
    ++stats_.received;
    if (lost_in_burst_ > 0) {
      spdlog::info("sim modem {}: a packet arrived intact again after {} lost to half-duplex or collisions", id_,
                   lost_in_burst_);
      lost_in_burst_ = 0;
    }
    deliver(arrival);
  }
}

int32_t SimDriver::curve_rate(const ModemTransmission& tx) {
  // Frameless packets (polls, ACKs) are FSK mini-packets: rate 0's curve.
  return tx.type() == ModemTransmission::DATA && tx.frame_size() > 0 ? tx.rate() : 0;
}

void SimDriver::set_prediction(const SimPhysics::Judgement& j, v1::ReceptionFigures* figures) {
  figures->set_predicted_tl_db(j.tl_db);
  figures->set_predicted_snr_db(j.predicted_snr_db);
}

bool SimDriver::decodes(Arrival& arrival) {
  const ModemTransmission& tx = arrival.envelope.transmission;
  arrival.judgement = physics_->judge(arrival.envelope.sender, arrival.envelope.position, position(), curve_rate(tx));
  if (!arrival.judgement->modelled) {
    if (stats_.lost_no_model++ == 0)
      spdlog::warn("sim modem {}: packet from {} lost: no TL grid from the model yet", id_, arrival.envelope.sender);
    return false;
  }
  // One draw: survive the fixed and range losses, then decode.
  const double p = (1.0 - loss_probability(arrival.range_m)) * arrival.judgement->probability;
  return uniform() < p;
}

void SimDriver::report_failed(const Arrival& arrival) {
  const auto& on_failed = sequence_.callbacks().on_reception_failed;
  if (!on_failed) return;
  const ModemTransmission& sent = arrival.envelope.transmission;
  ModemTransmission heard;
  heard.set_src(arrival.envelope.sender);
  heard.set_dest(sent.dest());
  heard.set_type(sent.type());
  heard.set_rate(curve_rate(sent));
  heard.set_time(util::seconds_since_epoch(arrival.interval.end));
  // What a modem can tell of a packet it failed to decode: not its SNR,
  // but the model still predicts one for the geometry.
  set_prediction(*arrival.judgement, heard.mutable_figures());
  heard.mutable_figures()->set_range_m(arrival.judgement->range_m);
  on_failed(heard);
}

void SimDriver::note_lost(const Arrival& arrival, const char* why) {
  if (lost_in_burst_++ == 0) {
    spdlog::warn("sim modem {}: packet from {} lost {} (further losses are counted in link status)", id_,
                 arrival.envelope.sender, why);
  } else {
    spdlog::debug("sim modem {}: packet from {} lost {}", id_, arrival.envelope.sender, why);
  }
}

void SimDriver::deliver(const Arrival& arrival) {
  ModemTransmission rx = arrival.envelope.transmission;
  rx.set_time(util::seconds_since_epoch(arrival.interval.end));
  char quality[96];
  std::snprintf(quality, sizeof quality, "sim range_m=%.1f delay_s=%.4f", arrival.range_m,
                arrival.range_m / sound_speed_);
  rx.set_link_quality(quality);
  if (arrival.judgement) {
    const SimPhysics::Judgement& j = *arrival.judgement;
    v1::ReceptionFigures* figures = rx.mutable_figures();
    figures->set_snr_in_db(j.snr_db);
    set_prediction(j, figures);
    figures->set_range_m(j.range_m);
    if (j.delay_spread_s) figures->set_delay_spread_s(*j.delay_spread_s);
    std::snprintf(quality, sizeof quality, "sim range_m=%.1f delay_s=%.4f snr_db=%.1f tl_db=%.1f", arrival.range_m,
                  arrival.range_m / sound_speed_, j.snr_db, j.tl_db);
    rx.set_link_quality(quality);
  }
  Clock::time_point answer_at = arrival.interval.end + kTurnaround;
  // The envelope says who really sent it: DATA under another node's id is a poll.
  sequence_.on_received(rx, {arrival.envelope.sender, [this, answer_at](std::function<void()> answer) {
                               send_when_free(answer_at, std::move(answer));
                             }});
}

void SimDriver::send_when_free(Clock::time_point when, std::function<void()> send) {
  schedule(when, [this, send = std::move(send)] {
    Clock::time_point now = scheduler_.clock().now();
    if (now < busy_until_) return send_when_free(busy_until_ + kTurnaround, send);
    send();
  });
}

}  // namespace acomms::drivers
