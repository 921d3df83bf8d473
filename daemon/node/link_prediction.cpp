#include "node/link_prediction.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/core_thread.h"
#include "gram/environment_validation.h"
#include "gram/link_physics.h"
#include "gram/model_pool.h"
#include "gram/tl_lookup.h"
#include "gram/vehicle_environment.h"

namespace acomms::node {
namespace {

constexpr double kBoundaryClearance = 1.0;  // m: the model has no field on a boundary
constexpr const char* kPrefix = "driver.micromodem.prediction.";

std::invalid_argument bad(const std::string& what) { return std::invalid_argument(kPrefix + what); }

double positive_or(double value, double fallback, const std::string& name) {
  if (value < 0 || !std::isfinite(value)) {
    throw bad(name + " must be > 0 (0: " + std::to_string(fallback) + "), got " + std::to_string(value));
  }
  return value > 0 ? value : fallback;
}

}  // namespace

std::shared_ptr<LinkPrediction> LinkPrediction::create(const drivers::MicroModemPrediction& c,
                                                       PredictionSources sources) {
  std::shared_ptr<LinkPrediction> p(new LinkPrediction());
  p->config_ = c;
  p->sources_ = std::move(sources);
  if (!std::isfinite(c.source_level_db()) || c.source_level_db() < 0 || c.source_level_db() > 300) {
    throw bad("source_level_db must be in [0, 300] dB re 1 uPa (0: 190), got " + std::to_string(c.source_level_db()));
  }
  p->source_level_db_ = c.source_level_db() > 0 ? c.source_level_db() : gram::kDefaultSourceLevelDb;
  if (c.noise_case() == drivers::MicroModemPrediction::kNoiseLevelDb &&
      (!std::isfinite(c.noise_level_db()) || std::abs(c.noise_level_db()) > 300)) {
    throw bad("noise_level_db must be a level within ±300 dB re 1 uPa, got " + std::to_string(c.noise_level_db()));
  }
  if (c.noise_case() == drivers::MicroModemPrediction::kNoiseModel) {
    const drivers::SimNoiseModel& m = c.noise_model();
    if (m.has_sea_state() && m.sea_state() > 6) throw bad("noise_model.sea_state must be in 0..6");
    if (m.has_shipping() && !(m.shipping() >= 0 && m.shipping() <= 1)) throw bad("noise_model.shipping must be in [0, 1]");
    (void)positive_or(m.band_hz(), 1, "noise_model.band_hz");
  }
  p->max_range_m_ = positive_or(c.max_range_m(), 5000, "max_range_m");
  p->range_step_m_ = positive_or(c.range_step_m(), 10, "range_step_m");
  if (p->max_range_m_ / p->range_step_m_ > 20000) throw bad("range_step_m is too fine: more than 20000 grid ranges");
  (void)positive_or(c.depth_step_m(), 1, "depth_step_m");
  p->depth_tolerance_m_ = positive_or(c.depth_tolerance_m(), 1, "depth_tolerance_m");
  p->max_age_s_ = positive_or(c.max_position_age_s(), 600, "max_position_age_s");
  for (int i = 0; i < c.fixed_size(); ++i) {
    const drivers::FixedModemPosition& f = c.fixed(i);
    const auto& q = f.position();
    if (!std::isfinite(q.x()) || !std::isfinite(q.y()) || !std::isfinite(q.z())) {
      throw bad("fixed[" + std::to_string(i) + "].position must be finite");
    }
    p->fixed_[static_cast<int32_t>(f.modem())] = core::NodeFix{0, q.x(), q.y(), q.z()};
  }
  return p;
}

std::optional<core::NodeFix> LinkPrediction::position_of(int32_t modem, bool own) const {
  std::optional<core::NodeFix> live;
  if (own && sources_.own != nullptr) live = sources_.own->latest();
  if (!own && sources_.others != nullptr) live = sources_.others->latest(modem);
  if (live && sources_.now_s && sources_.now_s() - live->time_s <= max_age_s_) return live;
  auto it = fixed_.find(modem);
  if (it != fixed_.end()) return it->second;
  return std::nullopt;
}

double LinkPrediction::model_depth(double z_up) const {
  return std::clamp(-z_up, top_m_ + kBoundaryClearance, bottom_m_ - kBoundaryClearance);
}

const LinkPrediction::Water& LinkPrediction::water() {
  // The version first: a change between the two costs one more resolve
  // later, never a stale water kept under a newer version.
  const uint64_t version = sources_.environment->version();
  if (water_ && water_->version == version) return *water_;
  Water w;
  w.version = version;
  try {
    std::vector<gram::Environment> resolved = sources_.environment->resolve(gram::Environment(), {}, false);
    if (resolved.empty()) {
      w.problem = "GRAM has no environment";
    } else {
      w.env = std::move(resolved.front());
    }
  } catch (const std::exception& e) {
    w.problem = std::string("GRAM's environment: ") + e.what();
  }
  if (w.problem.empty() && w.env.sound_speed_size() < 2) {
    w.problem = "GRAM's environment has no sound-speed profile (gram.base)";
  }
  if (w.problem.empty()) {
    w.env.clear_source_depth_m();
    w.env.set_irregular_receivers(false);
    w.env.clear_receiver_depth_m();
    w.env.clear_receiver_range_m();
    w.bytes = w.env.SerializeAsString();
    w.top_m = w.env.sound_speed(0).depth_m();
    w.bottom_m = w.env.sound_speed(w.env.sound_speed_size() - 1).depth_m();
    if (w.bottom_m - w.top_m <= 2 * kBoundaryClearance) w.problem = "GRAM's environment: the water is too shallow";
  }
  ++counters_.water_resolved;
  water_ = std::move(w);
  return *water_;
}

std::optional<LinkPrediction::GridRequest> LinkPrediction::grid_environment(double own_depth_m) {
  auto problem = [this](const std::string& why) -> std::optional<GridRequest> {
    if (why != last_problem_) spdlog::warn("link prediction: no prediction: {}", why);
    last_problem_ = why;
    return std::nullopt;
  };
  if (sources_.environment == nullptr || sources_.pool == nullptr) return problem("GRAM has no model pool");
  const Water& w = water();
  if (!w.problem.empty()) return problem(w.problem);
  top_m_ = w.top_m;
  bottom_m_ = w.bottom_m;
  const double depth = std::clamp(own_depth_m, top_m_ + kBoundaryClearance, bottom_m_ - kBoundaryClearance);
  const bool same_water = grid_ && w.bytes == grid_water_;
  if (same_water && std::abs(depth - grid_depth_m_) <= depth_tolerance_m_) return std::nullopt;  // the grid holds
  if (w.bytes == failed_water_ && std::abs(depth - failed_depth_m_) <= depth_tolerance_m_) return std::nullopt;
  // A new grid: only now is the environment copied and filled in.
  GridRequest request{w.env, w.bytes};
  gram::Environment& env = request.env;
  const double step = config_.depth_step_m() > 0 ? config_.depth_step_m() : gram::default_depth_step_m(bottom_m_ - top_m_);
  const auto nz = static_cast<int>(std::ceil((bottom_m_ - top_m_) / step - 1e-9));
  if (nz > 2000) return problem("depth_step_m is too fine for this water: more than 2000 grid depths");
  for (int i = 0; i <= nz; ++i) env.add_receiver_depth_m(std::min(bottom_m_, top_m_ + i * step));
  const auto nr = static_cast<int>(std::ceil(max_range_m_ / range_step_m_ - 1e-9));
  for (int i = 0; i <= nr; ++i) env.add_receiver_range_m(i * range_step_m_);
  env.set_box_range_m(std::max(env.box_range_m(), (nr + 1) * range_step_m_));
  env.set_box_depth_m(std::max(env.box_depth_m(), bottom_m_ + 1));
  env.set_source_depth_m(depth);
  if (auto invalid = gram::validate_environment(env)) {
    failed_water_ = w.bytes;
    failed_depth_m_ = depth;
    return problem("GRAM's environment: " + *invalid);
  }
  return request;
}

void LinkPrediction::follow(double own_depth_m) {
  if (pending_) return;  // one run at a time; the next packet checks again
  std::optional<GridRequest> grid = grid_environment(own_depth_m);
  if (!grid) return;
  pending_ = true;
  std::optional<gram::Environment> env(std::move(grid->env));
  // The key of the grid (and of a failure) is the water as resolved, the
  // one grid_environment compares: not the request's, whose box was widened.
  std::string water = std::move(grid->water);
  const double depth = env->source_depth_m();
  double noise_db = config_.noise_level_db();
  try {
    if (config_.noise_case() != drivers::MicroModemPrediction::kNoiseLevelDb) {
      gram::NoiseModelInput noise;
      noise.centre_hz = env->frequency_hz();
      noise.band_hz = gram::default_band_hz(noise.centre_hz);
      const drivers::SimNoiseModel& m = config_.noise_model();
      if (m.has_sea_state()) noise.sea_state = static_cast<int>(m.sea_state());
      if (m.band_hz() > 0) noise.band_hz = m.band_hz();
      if (m.has_shipping()) noise.shipping = m.shipping();
      noise_db = gram::modelled_noise_level_db(noise, std::string(kPrefix) + "noise_model.");
    }
  } catch (const std::exception& e) {
    pending_ = false;
    failed_water_ = water;
    failed_depth_m_ = depth;
    spdlog::warn("link prediction: no noise level: {}", e.what());
    return;
  }
  ++counters_.grid_requests;
  gram::ModelRequest request;
  request.kind = gram::ModelKind::kTransmissionLoss;
  request.environments = {std::move(*env)};
  std::weak_ptr<LinkPrediction> self = weak_from_this();
  auto to_core = sources_.to_core;
  sources_.pool->submit(
      std::move(request), "",
      [self, to_core, depth, noise_db, water = std::move(water)](gram::ModelOutcome outcome) {
        to_core([self, depth, noise_db, water, outcome = std::move(outcome)] {
          auto p = self.lock();
          if (!p) return;
          ACOMMS_ASSERT_CORE_THREAD();
          p->pending_ = false;
          if (outcome.status != gram::ModelStatus::kOk || !outcome.result || outcome.result->tl.empty()) {
            spdlog::error("link prediction: the model failed for depth {:.1f} m: {}", depth, outcome.message);
            p->failed_water_ = water;
            p->failed_depth_m_ = depth;
            return;
          }
          // Aliasing: the grid lives in the pool's (cached) result.
          p->grid_ = std::shared_ptr<const gram::TransmissionLoss>(outcome.result, &outcome.result->tl.at(0));
          p->grid_depth_m_ = depth;
          p->grid_noise_db_ = noise_db;
          p->grid_water_ = water;
          ++p->counters_.grids;
          spdlog::debug("link prediction: new TL grid for depth {:.1f} m", depth);
        });
      });
}

void LinkPrediction::predict(const v1::ModemTransmission& heard, v1::LinkFigures& figures) {
  ACOMMS_ASSERT_CORE_THREAD();
  const std::optional<core::NodeFix> own = position_of(sources_.own_id, true);
  const std::optional<core::NodeFix> from = position_of(heard.src(), false);
  if (!own || !from) {
    ++counters_.no_position;
    return;
  }
  follow(-own->z);
  if (!grid_) {
    ++counters_.no_model;
    return;
  }
  const double range = std::hypot(from->x - own->x, from->y - own->y);
  const double tl = range > max_range_m_ ? INFINITY : gram::tl_at(*grid_, range, model_depth(from->z));
  if (!std::isfinite(tl)) {
    ++counters_.out_of_range;
    return;
  }
  figures.set_predicted_tl_db(tl);
  figures.set_predicted_snr_db(source_level_db_ - tl - grid_noise_db_);
  ++counters_.predicted;
}

}  // namespace acomms::node
