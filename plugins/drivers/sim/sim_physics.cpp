#include "sim/sim_physics.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/core_thread.h"
#include "gram/bellhop_import.h"
#include "gram/environment_validation.h"
#include "gram/tl_lookup.h"
#include "link/rate_table.h"

namespace acomms::drivers {
namespace {

constexpr double kBoundaryClearance = 1.0;  // m: the model has no field on a boundary

std::invalid_argument bad(const std::string& what) { return std::invalid_argument("driver.sim.physics." + what); }

double positive_or(double value, double fallback, const std::string& name) {
  if (value < 0 || !std::isfinite(value)) throw bad(name + " must be > 0 (0: " + std::to_string(fallback) + "), got " + std::to_string(value));
  return value > 0 ? value : fallback;
}

gram::LinkPhysics physics_of(const SimPhysicsConfig& c, double frequency_hz) {
  gram::LinkPhysics physics;
  if (!std::isfinite(c.source_level_db()) || c.source_level_db() < 0 || c.source_level_db() > 300)
    throw bad("source_level_db must be in [0, 300] dB re 1 uPa (0: 190), got " + std::to_string(c.source_level_db()));
  physics.source_level_db = c.source_level_db() > 0 ? c.source_level_db() : gram::kDefaultSourceLevelDb;
  if (c.noise_case() == SimPhysicsConfig::kNoiseLevelDb) {
    if (!std::isfinite(c.noise_level_db()) || std::abs(c.noise_level_db()) > 300)
      throw bad("noise_level_db must be a level within ±300 dB re 1 uPa, got " + std::to_string(c.noise_level_db()));
    physics.noise_level_db = c.noise_level_db();
  } else {
    gram::NoiseModelInput noise;
    noise.centre_hz = frequency_hz;
    const SimNoiseModel& m = c.noise_model();
    if (m.has_sea_state()) noise.sea_state = static_cast<int>(std::min<uint32_t>(m.sea_state(), 1000));
    noise.band_hz = positive_or(m.band_hz(), gram::default_band_hz(frequency_hz), "noise_model.band_hz");
    if (m.has_shipping()) noise.shipping = m.shipping();
    physics.noise_level_db = gram::modelled_noise_level_db(noise, "driver.sim.physics.noise_model.");
  }
  physics.site.excess_loss_db = c.excess_loss_db();
  if (c.has_own_ship_noise_db()) physics.site.own_ship_noise_db = c.own_ship_noise_db();
  if (auto problem = gram::validate_site_correction(physics.site, "driver.sim.physics.")) throw std::invalid_argument(*problem);
  for (int i = 0; i < c.reception_size(); ++i) {
    const SimReceptionCurve& r = c.reception(i);
    const std::string name = "reception[" + std::to_string(i) + "].";
    if (!link::find_rate(r.rate())) throw bad(name + "rate must be in 0..5, got " + std::to_string(r.rate()));
    gram::ReceptionCurve curve{r.snr50_db(), r.slope_per_db() > 0 ? r.slope_per_db() : gram::kDefaultSlopePerDb};
    if (auto problem = gram::validate_reception_curve(curve, "driver.sim.physics." + name)) throw std::invalid_argument(*problem);
    physics.curves[r.rate()] = curve;
  }
  return physics;
}

}  // namespace

std::shared_ptr<SimPhysics> SimPhysics::create(const SimPhysicsConfig& c, int32_t own_id) {
  if (c.env_file().empty()) throw bad("env_file is required: the BELLHOP-format environment of the water");
  std::shared_ptr<SimPhysics> p(new SimPhysics());
  p->own_id_ = own_id;
  try {
    p->environment_ = gram::import_bellhop_env_file(c.env_file()).environment;
  } catch (const std::exception& e) {
    throw bad(std::string("env_file: ") + e.what());
  }
  p->physics_ = physics_of(c, p->environment_.frequency_hz());
  p->max_range_m_ = positive_or(c.max_range_m(), 5000, "max_range_m");
  p->range_step_m_ = positive_or(c.range_step_m(), 10, "range_step_m");
  p->depth_tolerance_m_ = positive_or(c.depth_tolerance_m(), 1, "depth_tolerance_m");
  if (p->max_range_m_ / p->range_step_m_ > 20000) throw bad("range_step_m is too fine: more than 20000 grid ranges");
  p->top_m_ = p->environment_.sound_speed(0).depth_m();
  p->bottom_m_ = p->environment_.sound_speed(p->environment_.sound_speed_size() - 1).depth_m();
  if (p->bottom_m_ - p->top_m_ <= 2 * kBoundaryClearance) throw bad("env_file: the water is too shallow to model");
  p->depth_step_m_ = positive_or(c.depth_step_m(), gram::default_depth_step_m(p->bottom_m_ - p->top_m_), "depth_step_m");
  if ((p->bottom_m_ - p->top_m_) / p->depth_step_m_ > 2000) throw bad("depth_step_m is too fine: more than 2000 grid depths");
  // The receiver grid, once: only the source depth changes between runs.
  gram::Environment& env = p->environment_;
  env.set_irregular_receivers(false);
  env.clear_receiver_depth_m();
  env.clear_receiver_range_m();
  const auto nz = static_cast<int>(std::ceil((p->bottom_m_ - p->top_m_) / p->depth_step_m_ - 1e-9));
  for (int i = 0; i <= nz; ++i) env.add_receiver_depth_m(std::min(p->bottom_m_, p->top_m_ + i * p->depth_step_m_));
  const auto nr = static_cast<int>(std::ceil(p->max_range_m_ / p->range_step_m_ - 1e-9));
  for (int i = 0; i <= nr; ++i) env.add_receiver_range_m(i * p->range_step_m_);
  env.set_box_range_m(std::max(env.box_range_m(), (nr + 1) * p->range_step_m_));
  env.set_box_depth_m(std::max(env.box_depth_m(), p->bottom_m_ + 1));
  env.set_source_depth_m(p->top_m_ + kBoundaryClearance);
  if (auto problem = gram::validate_environment(env)) throw bad("env_file: " + *problem);
  return p;
}

double SimPhysics::model_depth(const SimPosition& p) const {
  return std::clamp(-p.z, top_m_ + kBoundaryClearance, bottom_m_ - kBoundaryClearance);
}

std::optional<double> SimPhysics::grid_depth_m() const {
  if (!grid_) return std::nullopt;
  return grid_depth_m_;
}

void SimPhysics::follow(const SimPosition& own) {
  ACOMMS_ASSERT_CORE_THREAD();
  last_own_ = own;
  if (!source_ || pending_depth_m_) return;  // one run at a time; re-checked on its answer
  const double depth = model_depth(own);
  if (grid_ && std::abs(depth - grid_depth_m_) <= depth_tolerance_m_) return;
  if (failed_depth_m_ && std::abs(depth - *failed_depth_m_) <= depth_tolerance_m_) return;
  ask_grid(depth);
}

void SimPhysics::ask_grid(double depth_m) {
  pending_depth_m_ = depth_m;
  ModelRun run;
  run.environment = environment_;
  run.environment.set_source_depth_m(depth_m);
  std::weak_ptr<SimPhysics> self = weak_from_this();
  source_->request(std::move(run), [self, depth_m](ModelAnswer answer) {
    if (auto physics = self.lock()) physics->on_grid(depth_m, std::move(answer));
  });
}

void SimPhysics::on_grid(double depth_m, ModelAnswer answer) {
  ACOMMS_ASSERT_CORE_THREAD();
  pending_depth_m_.reset();
  if (!answer.tl) {
    // Keep the last grid, and do not ask for this depth again: it would
    // fail the same way, on every packet.
    spdlog::error("sim modem {}: the model failed for depth {:.1f} m: {}", own_id_, depth_m, answer.error);
    failed_depth_m_ = depth_m;
    return;
  }
  failed_depth_m_.reset();
  grid_ = std::move(answer.tl);
  grid_depth_m_ = depth_m;
  ++grids_received_;
  spdlog::debug("sim modem {}: new TL grid for depth {:.1f} m ({} beams)", own_id_, depth_m, grid_->beam_count);
  if (last_own_) follow(*last_own_);  // the node may have moved on meanwhile
}

SimPhysics::Judgement SimPhysics::judge(int32_t sender, const SimPosition& from, const SimPosition& own, int32_t rate) {
  ACOMMS_ASSERT_CORE_THREAD();
  follow(own);
  Judgement j;
  j.range_m = std::hypot(from.x - own.x, from.y - own.y);
  if (!grid_) return j;
  j.modelled = true;
  const double sender_depth = model_depth(from);
  const double tl_db = j.range_m > max_range_m_ ? INFINITY : gram::tl_at(*grid_, j.range_m, sender_depth);
  const gram::LinkOutcome outcome = gram::link_outcome(physics_, tl_db, rate);
  j.tl_db = outcome.tl_db;
  j.snr_db = outcome.snr_db;
  j.probability = outcome.probability;
  j.predicted_snr_db = physics_.source_level_db - outcome.tl_db - physics_.noise_level_db;
  Spread& spread = spreads_[sender];
  j.delay_spread_s = spread.delay_spread_s;
  const bool moved = spread.range_m < 0 || std::abs(spread.range_m - j.range_m) > 5 * range_step_m_ ||
                     std::abs(spread.sender_depth_m - sender_depth) > depth_tolerance_m_ ||
                     std::abs(spread.own_depth_m - grid_depth_m_) > depth_tolerance_m_;
  if (!spread.pending && moved && j.range_m > 0 && j.range_m <= max_range_m_)
    ask_spread(sender, j.range_m, sender_depth, grid_depth_m_);
  return j;
}

void SimPhysics::ask_spread(int32_t sender, double range_m, double sender_depth_m, double own_depth_m) {
  Spread& spread = spreads_[sender];
  spread.pending = true;
  spread.range_m = range_m;
  spread.sender_depth_m = sender_depth_m;
  spread.own_depth_m = own_depth_m;
  ModelRun run;
  run.kind = ModelRun::Kind::kDelaySpread;
  run.environment = environment_;
  run.environment.set_source_depth_m(own_depth_m);
  run.environment.clear_receiver_depth_m();
  run.environment.clear_receiver_range_m();
  run.environment.set_irregular_receivers(true);
  run.environment.add_receiver_range_m(range_m);
  run.environment.add_receiver_depth_m(sender_depth_m);
  std::weak_ptr<SimPhysics> self = weak_from_this();
  source_->request(std::move(run), [self, sender](ModelAnswer answer) {
    auto physics = self.lock();
    if (!physics) return;
    Spread& s = physics->spreads_[sender];
    s.pending = false;
    if (!answer.error.empty()) {
      spdlog::warn("sim modem {}: no delay spread for modem {}: {}", physics->own_id_, sender, answer.error);
      return;
    }
    s.delay_spread_s = answer.delay_spread_s;
  });
}

}  // namespace acomms::drivers
